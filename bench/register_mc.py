#!/usr/bin/env python3
"""Monte Carlo benchmark of rk-register on seed 002's scenarios (issue 5, docs/benchmarks.md).

For each scenario and run r (seed = seed0 + r) it simulates a trial with `rk-sim radar`, runs the
requested rk-register methods on it (the real binaries, with --quiet), and accumulates the
estimation errors against the simulator's truth. Runs go in parallel (--jobs, default 2) and are
deterministic per seed. Writes to --out:
  rmse_s<S>_<method>.csv   RMSE over the runs at every step, 12 biases (m and rad)
  fig_s<S>.png             radar a's six RMSE curves (the paper's Figs. 1-2 layout)
  tables.md                Table 1 (convergence step) and Table 2 (accuracy %) next to the paper's
  summary.json             everything above plus timings
Definitions (docs/rk-register.md, "Accuracy and convergence"):
  RMSE_k        = sqrt(mean over runs of e_k^2), e_k = estimate - truth at step k (1-based)
  convergence   = first step after which RMSE stays below 1e-3 rad (angles) / 30 m (range) to the end
  accuracy      = 100 (1 - mean over runs of |e_K| / |truth|) at the final step K   (primary)
  also reported: acc_rmse = 100 (1 - RMSE_K/|truth|); acc_post = 100 (1 - mean over runs and over the
  steps from convergence to K of |e_k|/|truth|); acc_mean = 100 (1 - |mean over runs of e_K|/|truth|).
Methods: after (bernoulli, defaults), before (bernoulli -L 1), kf1..kfN (kf --track i), kfall
(kf --track all), batch (batch, defaults), and any --variant NAME='bernoulli -K 1 -L 5'. Extra
rk-register options of a method: --extra 'after=--q 0.1,1e-5,1e-5,1e-5,1e-5,1e-5'.
Python standard library + matplotlib only.
"""
import argparse
import concurrent.futures as cf
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

BIASES = ["range_m", "az_deg", "el_deg", "yaw_deg", "pitch_deg", "roll_deg"]
NAMES = ["range", "azimuth", "elevation", "yaw", "pitch", "roll"]
# Seed 002, scenario 3, Tables 1 and 2 (radar a), before / after partition.
PAPER_CONV = {"before": [161, 330, 288, 362, 317, 305], "after": [18, 281, 194, 310, 260, 242]}
PAPER_ACC = {"before": [98.43, 96.52, 90.33, 93.25, 93.34, 92.14], "after": [98.66, 98.18, 95.04, 97.31, 96.71, 96.53]}
CONV_RANGE_M = 30.0
CONV_ANGLE_RAD = 1e-3


def to_si(index, value):
    """File units (m, deg) to SI (m, rad) for bias `index` within a radar block."""
    return value if index == 0 else math.radians(value)


VARIANTS = {}  # NAME -> rk-register arguments (--variant NAME='bernoulli -K 1 -L 5')


def method_args(method):
    if method in VARIANTS:
        return VARIANTS[method]
    if method == "after":
        return ["bernoulli"]
    if method == "before":
        return ["bernoulli", "-L", "1"]
    if method == "kfall":
        return ["kf", "--track", "all"]
    if method.startswith("kf"):
        return ["kf", "--track", method[2:]]
    if method == "batch":
        return ["batch"]
    raise SystemExit("unknown method " + method)


def run_one(args, scenario, seed, methods, extra):
    """Simulates one trial and runs every method; returns per-method error arrays and timings."""
    work = tempfile.mkdtemp(prefix="rk-mc-", dir=args.tmp)
    try:
        trial = os.path.join(work, "trial")
        t0 = time.perf_counter()
        subprocess.run([os.path.join(args.bin, "rk-sim"), "radar", "--out", trial, "--scenario", str(scenario),
                        "--steps", str(args.steps), "--seed", str(seed), "--quiet"] + args.sim_args,
                       check=True)
        t_sim = time.perf_counter() - t0
        scen = json.load(open(os.path.join(trial, "scenario.json")))
        radars = scen["options"]["names"]
        truth = []
        for r in radars:
            for i, b in enumerate(BIASES):
                truth.append(to_si(i, scen["radars"][r]["bias"][b]))
        out = {"truth": truth, "times": {"sim": t_sim}, "errors": {}}
        for m in methods:
            est = os.path.join(work, m + ".csv")
            cmd = [os.path.join(args.bin, "rk-register")] + method_args(m) + [
                "--plots", os.path.join(trial, "plots.csv"), "--nav", os.path.join(trial, "nav.csv"),
                "-o", est, "--quiet"] + extra.get(m, [])
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True)
            out["times"][m] = time.perf_counter() - t0
            errs = []
            with open(est) as f:
                rows = csv.DictReader(line for line in f if not line.startswith("#"))
                cols = [r + "_" + b for r in radars for b in BIASES]
                for row in rows:
                    errs.append([to_si(j % 6, float(row[c])) - truth[j] for j, c in enumerate(cols)])
            out["errors"][m] = errs
        return out
    finally:
        shutil.rmtree(work, ignore_errors=True)


class Acc:
    """Running sums over runs for one method."""

    def __init__(self):
        self.n = 0
        self.sq = None
        self.ab = None
        self.sm = None
        self.final = []

    def add(self, errs):
        if self.sq is None:
            self.sq = [[0.0] * 12 for _ in errs]
            self.ab = [[0.0] * 12 for _ in errs]
            self.sm = [[0.0] * 12 for _ in errs]
        steps = min(len(errs), len(self.sq))
        for k in range(steps):
            e, q, a, s = errs[k], self.sq[k], self.ab[k], self.sm[k]
            for j in range(12):
                q[j] += e[j] * e[j]
                a[j] += abs(e[j])
                s[j] += e[j]
        self.final.append(errs[-1])
        self.n += 1

    def rmse(self):
        return [[math.sqrt(v / self.n) for v in row] for row in self.sq]


def convergence_step(rmse, j):
    thr = CONV_RANGE_M if j % 6 == 0 else CONV_ANGLE_RAD
    last_bad = -1
    for k, row in enumerate(rmse):
        if not row[j] < thr:
            last_bad = k
    if last_bad == len(rmse) - 1:
        return None
    return last_bad + 2  # 1-based step of the first sample of the final below-threshold stretch


def metrics(acc, truth):
    rmse = acc.rmse()
    res = {"runs": acc.n, "convergence_step": [], "acc_final": [], "acc_rmse": [], "acc_post": [], "acc_mean": [],
           "rmse_final": rmse[-1]}
    for j in range(12):
        x = abs(truth[j])
        conv = convergence_step(rmse, j)
        res["convergence_step"].append(conv)
        res["acc_final"].append(100 * (1 - sum(abs(f[j]) for f in acc.final) / acc.n / x))
        res["acc_rmse"].append(100 * (1 - rmse[-1][j] / x))
        res["acc_mean"].append(100 * (1 - abs(sum(f[j] for f in acc.final) / acc.n) / x))
        if conv is None:
            res["acc_post"].append(None)
        else:
            ks = range(conv - 1, len(rmse))
            res["acc_post"].append(100 * (1 - sum(acc.ab[k][j] for k in ks) / len(ks) / acc.n / x))
    return res


def fmt(v, nd=2):
    if v is None:
        return "—"
    if isinstance(v, int):
        return str(v)
    return f"{v:.{nd}f}"


def plot(path, scenario, rmse_by_method, radar_name):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not available: no PNG", file=sys.stderr)
        return
    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    for j, ax in enumerate(axes.flat):
        for m, rm in rmse_by_method.items():
            style = {"after": ("k-", 1.6), "before": ("b--", 1.2), "batch": ("g-", 1.0)}.get(m, (":", 0.9))
            ax.semilogy(range(1, len(rm) + 1), [row[j] for row in rm], style[0], lw=style[1], label=m)
        ax.axhline(CONV_RANGE_M if j == 0 else CONV_ANGLE_RAD, color="r", lw=0.6, ls="-.")
        ax.set_title(f"radar {radar_name}: {NAMES[j]} bias RMSE ({'m' if j == 0 else 'rad'})")
        ax.set_xlabel("step")
        ax.grid(True, which="both", lw=0.3)
    axes.flat[0].legend(fontsize=8)
    fig.suptitle(f"Scenario {scenario}: RMSE over Monte Carlo runs (threshold red)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 allow_abbrev=False)
    ap.add_argument("--runs", type=int, default=100)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--scenarios", default="1,2,3")
    ap.add_argument("--methods", default="", help="comma list; default: 1,2: after,before,kf1..kf5; 3: after,before,batch")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed0", type=int, default=1)
    ap.add_argument("--bin", default="build/apps")
    ap.add_argument("--out", default="/tmp/rk-register-mc")
    ap.add_argument("--tmp", default="/dev/shm" if os.access("/dev/shm", os.W_OK) else None,
                    help="scratch folder for the trials (default /dev/shm: no disk syncs)")
    ap.add_argument("--extra", action="append", default=[], help="METHOD=options for rk-register")
    ap.add_argument("--variant", action="append", default=[],
                    help="NAME=ARGS: a method NAME running 'rk-register ARGS', e.g. k1l5='bernoulli -K 1 -L 5'")
    ap.add_argument("--sim-args", default="", help="extra rk-sim radar options, e.g. '--index-unit step'")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw fig_s<S>.png from the rmse_s<S>_<method>.csv files already in --out")
    args = ap.parse_args()
    if args.replot:
        import glob
        for scenario in [int(s) for s in args.scenarios.split(",")]:
            curves = {}
            for path in sorted(glob.glob(os.path.join(args.out, f"rmse_s{scenario}_*.csv"))):
                m = os.path.basename(path)[len(f"rmse_s{scenario}_"):-4]
                with open(path) as f:
                    curves[m] = [[float(v) for v in row[1:]] for row in list(csv.reader(f))[1:]]
            order = [m for m in ("after", "before", "batch") if m in curves] + sorted(
                m for m in curves if m not in ("after", "before", "batch"))
            plot(os.path.join(args.out, f"fig_s{scenario}.png"), scenario, {m: curves[m] for m in order}, "a")
        return
    args.sim_args = args.sim_args.split()
    for v in args.variant:
        k, _, a = v.partition("=")
        VARIANTS[k] = a.split()
    extra = {}
    for e in args.extra:
        k, _, v = e.partition("=")
        extra[k] = v.split()
    os.makedirs(args.out, exist_ok=True)
    summary = {"runs": args.runs, "steps": args.steps, "jobs": args.jobs, "seed0": args.seed0,
               "sim_args": args.sim_args, "extra": extra, "scenarios": {}}
    md = [f"# rk-register Monte Carlo: {args.runs} runs x {args.steps} steps, seeds {args.seed0}.."
          f"{args.seed0 + args.runs - 1}, {args.jobs} jobs", ""]
    for scenario in [int(s) for s in args.scenarios.split(",")]:
        methods = [m for m in args.methods.split(",") if m] or (
            ["after", "before", "batch"] if scenario == 3 else ["after", "before"] + [f"kf{i}" for i in range(1, 6)])
        accs = {m: Acc() for m in methods}
        times = {}
        truth = None
        t0 = time.perf_counter()
        with cf.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futs = [pool.submit(run_one, args, scenario, args.seed0 + r, methods, extra) for r in range(args.runs)]
            for fu in cf.as_completed(futs):
                res = fu.result()
                truth = res["truth"]
                for m in methods:
                    accs[m].add(res["errors"][m])
                for k, v in res["times"].items():
                    times[k] = times.get(k, 0.0) + v
        wall = time.perf_counter() - t0
        sc = {"wall_s": wall, "cpu_s_by_step": times, "methods": {}}
        for m in methods:
            met = metrics(accs[m], truth)
            sc["methods"][m] = met
            rm = accs[m].rmse()
            with open(os.path.join(args.out, f"rmse_s{scenario}_{m}.csv"), "w") as f:
                w = csv.writer(f)
                w.writerow(["step"] + [f"{r}_{n}" for r in ("a", "b") for n in ("range_m", "az_rad", "el_rad",
                                                                                   "yaw_rad", "pitch_rad", "roll_rad")])
                for k, row in enumerate(rm):
                    w.writerow([k + 1] + [f"{v:.9g}" for v in row])
        summary["scenarios"][scenario] = sc
        if not args.no_plot:
            plot(os.path.join(args.out, f"fig_s{scenario}.png"), scenario,
                 {m: accs[m].rmse() for m in methods}, "a")
        # Tables (radar a as in the paper; radar b below).
        md.append(f"## Scenario {scenario} ({wall:.1f} s wall for {args.runs} runs; "
                  + ", ".join(f"{k} {v:.1f} s" for k, v in times.items()) + " process time)")
        md.append("")
        for r, rname in ((0, "a"), (1, "b")):
            md.append(f"### Radar {rname}: convergence step (RMSE < 30 m / 1e-3 rad to the end)")
            md.append("")
            md.append("| method | " + " | ".join(NAMES) + " |")
            md.append("|---|" + "---|" * 6)
            if scenario == 3 and r == 0:
                for k in ("before", "after"):
                    md.append(f"| paper {k} | " + " | ".join(str(v) for v in PAPER_CONV[k]) + " |")
            for m in methods:
                cs = sc["methods"][m]["convergence_step"][6 * r:6 * r + 6]
                md.append(f"| {m} | " + " | ".join(fmt(v) for v in cs) + " |")
            md.append("")
            md.append(f"### Radar {rname}: accuracy % (acc_final; acc_rmse / acc_post / acc_mean in brackets)")
            md.append("")
            md.append("| method | " + " | ".join(NAMES) + " |")
            md.append("|---|" + "---|" * 6)
            if scenario == 3 and r == 0:
                for k in ("before", "after"):
                    md.append(f"| paper {k} | " + " | ".join(f"{v:.2f}" for v in PAPER_ACC[k]) + " |")
            for m in methods:
                mm = sc["methods"][m]
                cells = []
                for j in range(6 * r, 6 * r + 6):
                    cells.append(f"{fmt(mm['acc_final'][j])} ({fmt(mm['acc_rmse'][j])} / {fmt(mm['acc_post'][j])} / "
                                 f"{fmt(mm['acc_mean'][j])})")
                md.append(f"| {m} | " + " | ".join(cells) + " |")
            md.append("")
            md.append(f"### Radar {rname}: final RMSE (m, rad)")
            md.append("")
            md.append("| method | " + " | ".join(NAMES) + " |")
            md.append("|---|" + "---|" * 6)
            for m in methods:
                fr = sc["methods"][m]["rmse_final"][6 * r:6 * r + 6]
                md.append(f"| {m} | " + " | ".join(f"{v:.3g}" for v in fr) + " |")
            md.append("")
        print(f"scenario {scenario}: {args.runs} runs in {wall:.1f} s", file=sys.stderr)
    with open(os.path.join(args.out, "tables.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print("\n".join(md))


if __name__ == "__main__":
    main()
