#!/usr/bin/env python3
"""Golden outputs: run every tool on fixed-seed inputs and digest what it wrote.

A refactoring must not change behaviour. This script runs a fixed set of commands (the sample trial
through rk-run, a small rk-sim trial of every kind through rk-run, the subcommands rk-run does not
call, and malformed inputs) with the binaries in BIN, and writes one line per observable: every file a
command wrote (CSV, video, JSON), each command's exit code, standard output and standard error. Run
reports are compared with their volatile members removed (times, durations, file modification times,
versions, build identities, command lines); paths of the work folder and of BIN are replaced by
placeholders. Everything else must be byte-identical.

  golden_outputs.py BIN WORK [-o DIGESTS]          run and write the digests (stdout with -o -)
  golden_outputs.py BIN WORK --check DIGESTS       run and compare with a digest file: exit 1 on any difference
  golden_outputs.py BIN_A WORK --against BIN_B     run both and show the first differing bytes of each file

The digest file tests/golden/outputs.txt was made from the build before the redesign of issue 16
(commit 81c295d); tests/CMakeLists.txt checks every build against it (ctest -R golden_outputs). A commit
that changes behaviour on purpose rewrites it (-o) and says which observables changed and why: the option
tables of issue 16 changed one option-check message and the JSON reports (options blocks, summary), no
CSV or video product.
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Members of JSON reports that differ between two runs of the same binary, or between two builds of the
# same source: wall-clock times, durations, file times, tool identities (build ids, sizes), step keys.
VOLATILE_KEY = re.compile(
    r"(_utc$|^utc$|^time_s$|_time_s$|^elapsed|^seconds$|^wall|^cpu_|^mtime|^version$|^git_commit$|^build_id$|^tool_id$|"
    r"^command_line$|^argv$|^host|^pid$|^duration_ms$|^started|^finished|^tools_s$|^total_s$|"
    r"^identity$|^identities$|_ms$|cpu_s$|^time$|rss|^user_s$|^sys_s$|^key$|^upstream$|^tools$|^id$)")

# (name, shell command). Run in order in WORK with BIN first on PATH; $S is the repository.
COMMANDS = [
    # The sample trial shipped with the repository (the demo's input), through rk-run.
    ("sample", "cp -r \"$S/data/sample\" sample && rk-run sample --no-plots"),
    ("sample_again", "rk-run sample --no-plots"),  # every step up to date: skipped
    # One small simulated trial of each kind, through rk-run.
    ("sim_beacon", "rk-sim beacon --out beacon --preset small --duration 2 --seed 11 --occlusion 0.6:0.3 --quiet"),
    ("run_beacon", "rk-run beacon --no-plots"),
    ("sim_attitude", "printf '%s' '{\"width_px\": 1000, \"height_px\": 800, \"pixel_size_mm\": [0.00345, 0.00345], "
     "\"focal_length_mm\": 100.0, \"principal_point_px\": [499.5, 399.5], \"distortion\": [-0.02, 0, 0, 0, 0], "
     "\"mount_deg\": {\"yaw\": 0.02, \"pitch\": -0.01, \"roll\": 0.1}}' > att_cam.json && "
     "rk-sim attitude --out attitude --camera att_cam.json --range-m 40 --duration 1 --fps 10 --seed 12 "
     "--hide fin:0.3:0.3 --quiet"),
    ("run_attitude", "rk-run attitude --no-plots"),
    ("sim_theodolite", "rk-sim theodolite --out theo --sensor-px 640 --duration 0.2 --speed-mps 50 --images png "
     "--track-error-px 10 --seed 13 --quiet"),
    ("run_theodolite", "rk-run theo --no-plots"),
    ("sim_radar", "rk-sim radar --out radar --scenario 3 --steps 60 --seed 14 --quiet"),
    ("run_radar", "rk-run radar --no-plots"),
    ("sim_posetrack", "rk-sim posetrack --out pose --scenario head --duration 10 --seed 15 --dropout 0.1 --quiet"),
    # Subcommands rk-run does not call, on those trials.
    ("smooth_aukf", "rk-smooth aukf -i pose/measurements.csv --columns x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg -o aukf.csv --smooth --report aukf.json"),
    ("smooth_singer", "rk-smooth singer -i pose/measurements.csv --columns x_m,yaw_deg,roll_deg -o singer.csv --report singer.json"),
    ("smooth_resample", "rk-smooth resample -i pose/measurements.csv --columns y_m,pitch_deg --rate 7 --method cubic -o resampled.csv"),
    ("register_kf", "rk-register kf --plots radar/plots.csv --nav radar/nav.csv -o kf.csv --report kf.json"),
    ("register_bernoulli", "rk-register bernoulli --plots radar/plots.csv --nav radar/nav.csv -o bern.csv"),
    ("analyze_compare", "rk-analyze compare --estimate beacon/out/az/located.csv --reference beacon/truth/target.csv "
     "--columns az_deg,el_deg,range_m,e_m,n_m,u_m --arcsec --table --errors errors.csv -o compare.json"),
    ("analyze_budget", "rk-analyze budget --budget \"$S/data/seed004/budget_table2.json\" --samples 500 "
     "-o budget.json --table"),
    ("sim_device_help", "rk-sim device --help"),
    # Malformed input: message, exit code, no output.
    ("bad_track", "sed '4s/^\\([0-9]*\\),\\([0-9.]*\\),/\\1,\\2x,/' beacon/out/az/track.csv > bad_track.csv && "
     "rk-locate --track bad_track.csv --camera beacon/az/camera.json --turret beacon/turret.csv "
     "--range beacon/range.csv -o bad_located.csv --report bad_locate.json"),
    ("bad_manifest", "mkdir -p badtrial && printf '{\"name\": \"x\", \"cameras\": {\"az\": {\"video\": 3}}}\\n' "
     "> badtrial/trial.json && rk-run badtrial --no-plots"),
    ("bad_option", "rk-extract beacon --video beacon/az/video.mkv --frames beacon/az/frames.csv --window-min -3 "
     "-o never.csv"),
    ("bad_rows_skip", "sed '5d' beacon/turret.csv | sed '7s/$/,9/' > turret_bad.csv && rk-locate --track "
     "beacon/out/az/track.csv --camera beacon/az/camera.json --turret turret_bad.csv --range beacon/range.csv "
     "--bad-rows skip -o skip_located.csv --report skip.json"),
]


def normalise_json(v, video=False):
    if isinstance(v, dict):
        video = video or any(isinstance(x, str) and x.endswith(".mkv") for x in v.values())
        # A Matroska file holds a random segment identity and its writing date: its digest differs on
        # every run (its frames are compared by decoding, below).
        return {k: normalise_json(x, k.endswith(".mkv") or video) for k, x in v.items()
                if not VOLATILE_KEY.search(k) and not (video and k in ("sha256", "digest"))}
    if isinstance(v, list):
        return [normalise_json(x, video) for x in v]
    return v


def normalise_text(data, subs):
    text = data.decode("utf-8", "replace")
    for a, b in subs:
        text = text.replace(a, b)
    text = re.sub(r"\d{4}-\d\d-\d\dT\d\d:\d\d:[0-9.]+Z", "<utc>", text)
    text = re.sub(r"(out|\.rk-run)\.(tmp|old)\.\w+", r"\1.\2.<r>", text)  # rk-run's temporary folders
    text = re.sub(r"\[\d+\]", "[<pid>]", text)
    # Durations printed in tables and summary lines ("1.47", "in 4.72 s", "tools 3.23 s").
    text = re.sub(r"\b\d+\.\d+ s\b", "<s> s", text)
    return text


def digest_file(path, subs):
    with open(path, "rb") as f:
        data = f.read()
    name = os.path.basename(path)
    if name.endswith(".mkv"):
        data = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "framemd5", "-"], check=True,
                              capture_output=True).stdout
    elif name.endswith(".json"):
        try:
            doc = normalise_json(json.loads(data))
            data = normalise_text(json.dumps(doc, sort_keys=True).encode(), subs).encode()
        except ValueError:
            pass
    elif name.endswith(".log") or name == "rk-run.log":
        data = re.sub(r"\d+\.\d+", "<n>", normalise_text(data, subs)).encode()
    return hashlib.sha256(data).hexdigest(), data


def run_all(bin_dir, work, keep_bytes=False):
    bin_dir = os.path.abspath(bin_dir)
    work = os.path.abspath(work)
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(work)
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"], S=ROOT)
    subs = [(work, "<WORK>"), (bin_dir, "<BIN>"), (ROOT, "<SRC>")]
    out = {}
    seen = {}
    for name, cmd in COMMANDS:
        p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, capture_output=True)
        for stream, data in (("stdout", p.stdout), ("stderr", p.stderr)):
            text = normalise_text(data, subs)
            if name.startswith("run_") or name.startswith("sample"):
                # rk-run's time_s column, right-aligned: its padding depends on the time's digits too.
                text = re.sub(r"(?m)^(\S+\s+\S+)\s+\d+\.\d+", r"\1 <t>", text)
            out["cmd %s %s" % (name, stream)] = (hashlib.sha256(text.encode()).hexdigest(), text.encode())
        out["cmd %s exit" % name] = (str(p.returncode), str(p.returncode).encode())
        for dirpath, dirnames, filenames in os.walk(work):
            dirnames.sort()
            for fn in sorted(filenames):
                path = os.path.join(dirpath, fn)
                rel = os.path.relpath(path, work)
                st = os.stat(path)
                key = (st.st_mtime_ns, st.st_size)
                if seen.get(rel) == key:
                    continue
                seen[rel] = key
                if fn in ("last-run.json",) or fn.startswith(".") or "/.rk-run" in rel:
                    pass
                out["file %s" % rel] = digest_file(path, subs)
    if not keep_bytes:
        out = {k: (v[0], None) for k, v in out.items()}
    return out


def write(out, dest):
    lines = ["%s  %s\n" % (v[0], k) for k, v in sorted(out.items())]
    if dest == "-":
        sys.stdout.writelines(lines)
    else:
        with open(dest + ".tmp", "w") as f:
            f.writelines(lines)
        os.replace(dest + ".tmp", dest)


def read(path):
    d = {}
    with open(path) as f:
        for line in f:
            h, k = line.rstrip("\n").split("  ", 1)
            d[k] = h
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False)
    ap.add_argument("bin")
    ap.add_argument("work")
    ap.add_argument("-o", dest="out")
    ap.add_argument("--check")
    ap.add_argument("--against")
    a = ap.parse_args()
    if a.against:
        x = run_all(a.bin, a.work + "/a", keep_bytes=True)
        y = run_all(a.against, a.work + "/b", keep_bytes=True)
        bad = 0
        for k in sorted(set(x) | set(y)):
            if k not in x or k not in y:
                print("only in %s: %s" % ("A" if k in x else "B", k))
                bad += 1
            elif x[k][0] != y[k][0]:
                bad += 1
                xa, yb = x[k][1], y[k][1]
                i = next((i for i in range(min(len(xa), len(yb))) if xa[i] != yb[i]), min(len(xa), len(yb)))
                print("differs: %s at byte %d\n  A: %r\n  B: %r" % (k, i, xa[max(0, i - 60):i + 60],
                                                                   yb[max(0, i - 60):i + 60]))
        print("%d of %d observables differ" % (bad, len(set(x) | set(y))))
        return 1 if bad else 0
    got = run_all(a.bin, a.work)
    if a.check:
        want = read(a.check)
        bad = [k for k in sorted(set(want) | set(got)) if want.get(k) != (got[k][0] if k in got else None)]
        for k in bad:
            print("differs from %s: %s" % (a.check, k))
        print("%d of %d observables differ" % (len(bad), len(want)))
        if bad:
            write(got, os.path.join(a.work, "outputs.txt"))
            print("this build's digests: %s" % os.path.join(a.work, "outputs.txt"))
        return 1 if bad else 0
    write(got, a.out or "-")
    return 0


if __name__ == "__main__":
    sys.exit(main())
