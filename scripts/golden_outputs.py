#!/usr/bin/env python3
"""Golden outputs: run every tool on fixed-seed inputs and digest what it wrote.

A refactoring must not change behaviour. This script runs a fixed set of commands (the sample trial
through rk-run, a small rk-sim trial of every kind through rk-run, the subcommands rk-run does not
call, and malformed inputs) with the binaries in BIN, and writes one line per observable: every file a
command wrote (CSV, video, JSON), each command's exit code, standard output and standard error. Run
reports are compared with their volatile members removed (times, durations, file modification times,
versions, build identities, command lines); paths of the work folder and of BIN are replaced by
placeholders. Everything else must be byte-identical, except the numbers listed in TOLERANT below.

Numbers compared with a tolerance. Two computations are not reproducible to the bit on another processor, and
nothing is wrong with either machine's result:
- rk-attitude cylinder's image fit (theo/...): its model blurs the target's coverage with cv::sepFilter2D in
  single precision, and OpenCV picks that filter's SIMD code at run time by the processor (SSE4.1, AVX2 with
  FMA, AVX-512), so the blurred image differs in the last bits from one processor to another
  (OPENCV_CPU_DISABLE=AVX2 on this machine shows it). The Levenberg-Marquardt fit, whose Jacobian is a forward
  difference of that image, then takes another path (±1 iteration, ±5 % model evaluations) and stops at
  another point within its stopping tolerance: measured 0.004 σ in yaw and pitch, bounded by the stop rule at
  0.063 σ (below);
- glibc's libm picks its exp/log/sin/cos/pow code by the processor too (FMA and AVX2 variants;
  GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F makes this machine take the others — glibc 2.33 and later
  spell the features without the older "_Usable" suffix, which is silently ignored): the radar registrations
  (kf, batch) and the budget's Monte Carlo then differ by rounding (≤ 7e-13 relative in the JSON reports, the
  last printed digit of kf.csv).
Everything else, the image fit's inputs included, is exact and keeps its byte digest. Proven on one machine:
the check passes as it is, with GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F, and with that and
OPENCV_CPU_DISABLE=AVX512-SKX,AVX2,FMA3,AVX (the 8 tolerant observables differed byte-wise); and the test
golden_outputs_catches_a_change (tests/cli/golden_outputs_change.sh) fails it with one number changed by 1e-6.
A computation found to differ on another processor goes into TOLERANT with its tolerance and the reason
(--against shows which numbers differ and by how much).

Digest file format (tests/golden/outputs.txt), one observable a line, sorted:
  SHA256  KEY                      KEY = "cmd NAME stdout|stderr", "file PATH" (PATH relative to WORK);
  CODE  cmd NAME exit              the exit code itself;
  num  KEY  COLUMN  V1,V2,...      the numbers of one tolerant column of a CSV (COLUMN = its header name, the
                                   values as written, one per row, empty for an empty cell), or of one tolerant
                                   member of a JSON file (COLUMN = its path, /steps/1/quality/..., one value).
A tolerant observable's SHA256 is that of its text with every tolerant number replaced by "~", so the rest of
it is still compared byte for byte; its numbers are compared with TOLERANT's tolerances.

  golden_outputs.py BIN WORK [-o DIGESTS]          run and write the digests (stdout with -o -)
  golden_outputs.py BIN WORK --check DIGESTS       run and compare with a digest file: exit 1 on any difference
  golden_outputs.py BIN_A WORK --against BIN_B     run both and show the first differing bytes of each file
                                                   (and every tolerant number out of its tolerance)
  golden_outputs.py BIN WORK --check DIGESTS --no-run [--only REGEX]
                                                   no run: check the files a run left in WORK (e.g. with
                                                   a number changed on purpose), or those REGEX finds

The digest file tests/golden/outputs.txt was made from the build before the redesign of issue 16
(commit 81c295d); tests/CMakeLists.txt checks every build against it (ctest -R golden_outputs). A commit
that changes behaviour on purpose rewrites it (-o) and says which observables changed and why: the option
tables of issue 16 changed one option-check message and the JSON reports (options blocks, summary), no
CSV or video product.
"""
import argparse
import hashlib
import json
import math
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


# The image fit stops when its Gauss-Newton step would lower the cost by less than 1e-3 of the residual
# variance (lib/attitude/cylinder_image_fit.cc, pass 2): each machine's result is then within sqrt(1e-3) of a
# σ of the minimum, two machines within twice that. Fit results are compared to that bound, in each row's σ.
FIT_STOP_SIGMA = 2 * math.sqrt(1e-3)  # 0.063
# Rounding of another libm: ≤ 7e-13 of max(|value|, 1) measured; 1e-10 leaves 150 times that and still sees a
# change of 1e-6 in any value below 10^4.
LIBM_SCALED = 1e-10


def sigma_of(column, k=FIT_STOP_SIGMA):
    return ("sigma", column, k)


# file (regex on its path in WORK) -> [(column or JSON member path (regex, full match), tolerance)], first
# match wins. Tolerances: ("abs", x): |a - b| <= x; ("scaled", x): |a - b| <= x * max(|a|, 1); ("sigma", C, k):
# |a - b| <= k * the row's value of column C (as recorded); ("count", f, n): |a - b| <= max(n, f * |a|).
TOLERANT = [
    (r"theo/out/theo/axis\.csv", [
        (r"yaw_deg|alt_yaw_deg|separation_deg", sigma_of("sigma_yaw_deg")),
        (r"pitch_deg|alt_pitch_deg", sigma_of("sigma_pitch_deg")),
        # The σ are those of the fit at its stopping point: 1 % of themselves (measured: 1e-4).
        (r"sigma_yaw_deg|sigma_pitch_deg", ("scaled", 1e-2)),
        # The range along the line of sight (the image sees it through the target's scale): measured 2.1e-4 m
        # between OpenCV's SIMD variants; 5 mm is 25 times that and 4e-6 of the 1.1 km range.
        (r"range_(nose|tail1|tail2)_m", ("abs", 5e-3)),
        # The fit's nuisance figures, written with 3-4 decimals: two units of the last one.
        (r"fit_rms_dn", ("abs", 2e-3)), (r"fit_psf_px|fit_cone_m", ("abs", 2e-4)),
        # Iterations to the stop rule depend on the path: measured ±1 a frame.
        (r"fit_iterations", ("count", 0.0, 2)),
    ]),
    # The fit's model evaluations (measured ±5 % between OpenCV's variants; a change of the fit's cost beyond
    # 25 % is a change to record), and the digest and size of axis.csv, whose numbers are compared above.
    (r"theo/out/report\.json", [
        (r".*/model_evaluations", ("count", 0.25, 0)),
        (r"/steps/\d+/outputs/\d+/(sha256|bytes)", ("product", r"theo/axis\.csv")),
    ]),
    (r"theo/out/steps/theo\.attitude-cylinder\.report\.json", [(r".*/model_evaluations", ("count", 0.25, 0))]),
    # Radar registration and the error budget's Monte Carlo: every floating-point number, to rounding.
    (r"kf\.json|budget\.json|radar/out/report\.json|radar/out/steps/radar\.register-batch\.report\.json",
     [(r".*", ("scaled", LIBM_SCALED))]),
    # kf.csv is written with 9 decimals: another libm flips the last one (measured 1e-9); two units of it.
    (r"kf\.csv", [(r"(a|b)_\w+_(m|deg)", ("abs", 2e-9))]),
]


def tolerant_rules(rel):
    for pattern, rules in TOLERANT:
        if re.fullmatch(pattern, rel):
            return rules
    return None


def rule_for(rules, column):
    return next((tol for pattern, tol in rules if re.fullmatch(pattern, column)), None)


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def mask_csv(data, rules):
    """(text with the tolerant cells replaced by "~", {column: [cells]}) of a CSV observable."""
    lines, header, cols, nums = data.decode().split("\n"), None, [], {}
    for i, line in enumerate(lines):
        if not line or line.startswith("#"):
            continue
        cells = line.split(",")
        if header is None:
            header = cells
            cols = [(j, c) for j, c in enumerate(header) if rule_for(rules, c)]
            nums = {c: [] for _, c in cols}
            continue
        for j, c in cols:
            nums[c].append(cells[j] if j < len(cells) else "")
            if j < len(cells):
                cells[j] = "~"
        lines[i] = ",".join(cells)
    return "\n".join(lines).encode(), {c: ",".join(v) for c, v in nums.items()}


def mask_json(doc, rules, path="", nums=None):
    """(doc with the tolerant numbers replaced by "~", {member path: value}) of a JSON observable. A
    ("product", FILE) member (the digest and size of a tolerant product in an rk-run report) is replaced
    and not recorded: the product's own numbers are."""
    nums = {} if nums is None else nums
    if isinstance(doc, dict):
        out = {}
        for k, v in doc.items():
            p = path + "/" + k
            tol = rule_for(rules, p) if not isinstance(v, (dict, list)) else None
            if tol and tol[0] == "product":
                out[k] = "~" if re.search(tol[1] + "$", str(doc.get("path", ""))) else v
            else:
                out[k] = mask_json(v, rules, p, nums)[0]
        return out, nums
    if isinstance(doc, list):
        return [mask_json(v, rules, path + "/%d" % i, nums)[0] for i, v in enumerate(doc)], nums
    tol = rule_for(rules, path)
    # "scaled" (rounding) is for floating-point numbers only: integers, counts, stay exact.
    if tol and is_number(doc) and (tol[0] != "scaled" or isinstance(doc, float)):
        nums[path] = repr(doc)
        return "~", nums
    return doc, nums


def within(tol, want, got, row_of):
    """Whether the number `got` (text) is within `tol` of the recorded `want` (text); row_of(column) gives the
    recorded value of another column in the same row (for ("sigma", C, k))."""
    if want == "" or got == "":
        return want == got
    try:
        a, b = float(want), float(got)
    except ValueError:
        return want == got
    kind = tol[0]
    if kind == "abs":
        limit = tol[1]
    elif kind == "scaled":
        limit = tol[1] * max(abs(a), 1.0)
    elif kind == "sigma":
        try:
            limit = tol[2] * abs(float(row_of(tol[1])))
        except (TypeError, ValueError):
            return a == b
    else:  # count
        limit = max(tol[2], tol[1] * abs(a))
    return abs(a - b) <= limit


def compare_numbers(key, column, want, got):
    """None when every number of one tolerant column (or member) is within its tolerance, else why not."""
    rules = tolerant_rules(key[len("file "):]) or []
    tol = rule_for(rules, column)
    w, g = want[(key, column)].split(","), got[(key, column)].split(",")
    if len(w) != len(g) or tol is None:
        return "%d values, recorded %d" % (len(g), len(w))
    for i, (x, y) in enumerate(zip(w, g)):
        def row_of(c, i=i):
            other = want.get((key, c))
            return other.split(",")[i] if other is not None else None
        if not within(tol, x, y, row_of):
            return "row %d: %s, recorded %s (tolerance %s)" % (i + 1, y, x, tol)
    return None


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


def digest_file(path, subs, rel):
    """(sha256, the bytes digested, {column: numbers} of a tolerant observable, else {})."""
    with open(path, "rb") as f:
        data = f.read()
    name = os.path.basename(path)
    rules, nums = tolerant_rules(rel), {}
    if name.endswith(".mkv"):
        data = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "framemd5", "-"], check=True,
                              capture_output=True).stdout
    elif name.endswith(".json"):
        try:
            doc = normalise_json(json.loads(data))
            if rules:
                doc, nums = mask_json(doc, rules)
            data = normalise_text(json.dumps(doc, sort_keys=True).encode(), subs).encode()
        except ValueError:
            pass
    elif name.endswith(".log") or name == "rk-run.log":
        data = re.sub(r"\d+\.\d+", "<n>", normalise_text(data, subs)).encode()
    elif rules and name.endswith(".csv"):
        data, nums = mask_csv(data, rules)
    return hashlib.sha256(data).hexdigest(), data, nums


def digest_files(work, subs, out, nums, seen, only=None):
    """Digests every file of WORK not digested as it is now (seen: path -> (mtime, size)) into out/nums; with
    `only` (a regex), the files whose observable ("file PATH") it finds."""
    for dirpath, dirnames, filenames in os.walk(work):
        dirnames.sort()
        for fn in sorted(filenames):
            path = os.path.join(dirpath, fn)
            rel = os.path.relpath(path, work)
            if only and not re.search(only, "file " + rel):
                continue
            st = os.stat(path)
            key = (st.st_mtime_ns, st.st_size)
            if seen.get(rel) == key:
                continue
            seen[rel] = key
            h, data, cols = digest_file(path, subs, rel)
            out["file %s" % rel] = (h, data)
            for c in [k for k in nums if k[0] == "file %s" % rel]:
                del nums[c]
            for c, v in cols.items():
                nums[("file %s" % rel, c)] = v


def run_all(bin_dir, work, keep_bytes=False, run=True, only=None):
    """({observable: (digest, bytes or None)}, {(observable, column): numbers}) of the commands run with BIN in
    WORK (a new folder); with run=False, of the files already in WORK (its commands' output not known)."""
    bin_dir = os.path.abspath(bin_dir)
    work = os.path.abspath(work)
    subs = [(work, "<WORK>"), (bin_dir, "<BIN>"), (ROOT, "<SRC>")]
    out, nums, seen = {}, {}, {}
    if not run:
        digest_files(work, subs, out, nums, seen, only)
        return ({k: (v[0], v[1] if keep_bytes else None) for k, v in out.items()}, nums)
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(work)
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"], S=ROOT)
    for name, cmd in COMMANDS:
        p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, capture_output=True)
        for stream, data in (("stdout", p.stdout), ("stderr", p.stderr)):
            text = normalise_text(data, subs)
            if name.startswith("run_") or name.startswith("sample"):
                # rk-run's time_s column, right-aligned: its padding depends on the time's digits too.
                text = re.sub(r"(?m)^(\S+\s+\S+)\s+\d+\.\d+", r"\1 <t>", text)
            out["cmd %s %s" % (name, stream)] = (hashlib.sha256(text.encode()).hexdigest(), text.encode())
        out["cmd %s exit" % name] = (str(p.returncode), str(p.returncode).encode())
        digest_files(work, subs, out, nums, seen)
    if not keep_bytes:
        out = {k: (v[0], None) for k, v in out.items()}
    return out, nums


def write(out, nums, dest):
    # By observable, each tolerant one's numbers after its digest line, by column.
    rows = [((k, ""), "%s  %s\n" % (v[0], k)) for k, v in out.items()] + \
           [((k, c), "num  %s  %s  %s\n" % (k, c, v)) for (k, c), v in nums.items()]
    lines = [line for _, line in sorted(rows)]
    if dest == "-":
        sys.stdout.writelines(lines)
    else:
        with open(dest + ".tmp", "w") as f:
            f.writelines(lines)
        os.replace(dest + ".tmp", dest)


def read(path):
    d, nums = {}, {}
    with open(path) as f:
        for line in f:
            h, k = line.rstrip("\n").split("  ", 1)
            if h == "num":
                key, column, values = k.split("  ", 2)
                nums[(key, column)] = values
            else:
                d[k] = h
    return d, nums


def differences(want, want_nums, got, got_nums, only=None):
    """[(observable, why)] where got differs from want: a digest, or a tolerant number out of tolerance; with
    `only` (a regex), of the observables it finds."""
    if only:
        want = {k: v for k, v in want.items() if re.search(only, k)}
        want_nums = {k: v for k, v in want_nums.items() if re.search(only, k[0])}
    bad = []
    for k in sorted(set(want) | set(got)):
        if want.get(k) != (got[k][0] if k in got else None):
            bad.append((k, "digest" if k in want and k in got else ("missing" if k in want else "not recorded")))
    for kc in sorted(set(want_nums) | set(got_nums)):
        if kc not in want_nums or kc not in got_nums:
            bad.append(("%s  %s" % kc, "number not recorded" if kc in got_nums else "number missing"))
            continue
        why = compare_numbers(kc[0], kc[1], want_nums, got_nums)
        if why:
            bad.append(("%s  %s" % kc, why))
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False)
    ap.add_argument("bin")
    ap.add_argument("work")
    ap.add_argument("-o", dest="out")
    ap.add_argument("--check")
    ap.add_argument("--against")
    ap.add_argument("--no-run", action="store_true",
                    help="with --check: run nothing, check the files already in WORK (BIN is only the path "
                         "written in them); the commands' exit codes and output are not checked")
    ap.add_argument("--only", metavar="REGEX",
                    help="with --no-run: only the file observables whose key (\"file PATH\") the regex finds")
    a = ap.parse_args()
    if a.no_run and not a.check:
        ap.error("--no-run needs --check")
    if a.only and not a.no_run:
        ap.error("--only needs --no-run")
    if a.against:
        x, xn = run_all(a.bin, a.work + "/a", keep_bytes=True)
        y, yn = run_all(a.against, a.work + "/b", keep_bytes=True)
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
        for k, why in differences({}, xn, {}, yn):
            print("differs: %s: %s" % (k, why))
            bad += 1
        print("%d of %d observables differ" % (bad, len(set(x) | set(y))))
        return 1 if bad else 0
    got, got_nums = run_all(a.bin, a.work, run=not a.no_run, only=a.only or ("^file " if a.no_run else None))
    if a.check:
        want, want_nums = read(a.check)
        bad = differences(want, want_nums, got, got_nums, only=a.only or ("^file " if a.no_run else None))
        for k, why in bad:
            print("differs from %s: %s (%s)" % (a.check, k, why))
        print("%d of %d observables differ (%d numbers compared with a tolerance)"
              % (len(bad), len(want), len(want_nums)))
        if bad and not a.no_run:
            write(got, got_nums, os.path.join(a.work, "outputs.txt"))
            print("this build's digests: %s" % os.path.join(a.work, "outputs.txt"))
        return 1 if bad else 0
    write(got, got_nums, a.out or "-")
    return 0


if __name__ == "__main__":
    sys.exit(main())
