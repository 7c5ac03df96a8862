#!/usr/bin/env bash
# Issue 7 target: reprocessing 20 sample trials on this machine takes a total wall time within 10 % of
# (sum of the tools' own times) / (cores used). Generates N small beacon trials with rk-sim (kept between
# runs in ROOT; --regen makes them anew), runs `rk-nightly ROOT --force -j JOBS` and prints, from its
# summary, the wall time, the sum of the tool times (each step's wall time measured by rk-run around the
# child process), the ideal wall time tools / cores and their ratio; then a second rk-nightly run, where
# every trial is up to date.
#   bench/rk_nightly_bench.sh [--trials N] [--duration S] [--jobs J] [--no-plots] [--root DIR] [--regen]
#                             [--kind beacon|theodolite] [--no-image-fit] [--pages]
# Defaults: 20 trials, 10 s each (200 frames of 640x512, FFV1), J = nproc, plots on, ROOT=/tmp/rk-nightly-bench.
# --kind theodolite (issue 20): seed 004 theodolite trials instead (rk-sim theodolite --images mkv: 1536x1536
# frames at 20 Hz, the target ≈ 300 px), default 2 s each (41 frames), ROOT=/tmp/rk-nightly-bench-theo; the
# table then adds, per trial, the attitude-cylinder step's wall time, its method and the image fit's seconds,
# fits and model evaluations (from out/report.json). --no-image-fit sets "image-fit": false in every trial's
# "steps" (the three-point solve; without it the key is removed), to measure what the image fit adds.
# Release figures for docs/benchmarks.md "Issue 20":
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j && \
#   bench/rk_nightly_bench.sh --kind theodolite --trials 4 --jobs 1 --no-plots && \
#   bench/rk_nightly_bench.sh --kind theodolite --trials 4 --jobs 1 --no-plots --no-image-fit
# --pages (issue 19 targets; issue 34: with the KML/CZML exports) then measures what the report pages, the
# index and the exports add: four more forced passes, alternately without the export steps and with rk-report
# replaced by a no-op (a copy of rk-run in a folder of links to the tools, where it
# looks first) and with the real pages, the smaller wall of each and the difference (target <= 10 %);
# every page made again by hand, timed one by one (sum / cores = the pages' share of an ideal nightly); the
# index's own time from rk-nightly's log; and a 20-second beacon trial's page opened in headless Chromium
# five times (tests/cli/browser_check.py: load event end and first paint, target < 1 s).
set -euo pipefail
SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${RK_BIN:-$SRC/build/apps}
N=20; DUR=""; JOBS=$(nproc); PLOTS=""; ROOT=""; REGEN=0; KIND=beacon; FIT=1; PAGES=0
while [ $# -gt 0 ]; do
  case "$1" in
    --trials) N=$2; shift 2 ;;
    --duration) DUR=$2; shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --no-plots) PLOTS=--no-plots; shift ;;
    --root) ROOT=$2; shift 2 ;;
    --regen) REGEN=1; shift ;;
    --pages) PAGES=1; shift ;;
    --kind) KIND=$2; shift 2 ;;
    --no-image-fit) FIT=0; shift ;;
    *) echo "rk_nightly_bench.sh: error: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$KIND" in
  beacon) DUR=${DUR:-10}; ROOT=${ROOT:-/tmp/rk-nightly-bench} ;;
  theodolite) DUR=${DUR:-2}; ROOT=${ROOT:-/tmp/rk-nightly-bench-theo} ;;
  *) echo "rk_nightly_bench.sh: error: --kind must be beacon or theodolite" >&2; exit 2 ;;
esac
[ "$REGEN" = 1 ] && rm -rf "$ROOT"
mkdir -p "$ROOT"
made=0
for k in $(seq -w 1 "$N"); do
  if [ ! -s "$ROOT/t$k/trial.json" ]; then
    if [ "$KIND" = beacon ]; then
      "$BIN/rk-sim" beacon --out "$ROOT/t$k" --force --preset small --duration "$DUR" --seed "$((10#$k))" --quiet &
    else
      rm -rf "$ROOT/t$k"
      "$BIN/rk-sim" theodolite --out "$ROOT/t$k" --images mkv --duration "$DUR" --seed "$((10#$k))" --quiet &
    fi
    made=$((made + 1))
    if [ $((made % JOBS)) = 0 ]; then wait; fi
  fi
done
wait
if [ "$KIND" = theodolite ]; then
  for k in $(seq -w 1 "$N"); do
    python3 - "$ROOT/t$k/trial.json" "$FIT" <<'PY'
import json, sys
p, fit = sys.argv[1], sys.argv[2] == "1"
m = json.load(open(p))
steps = m.get("steps") or {}
if fit:
    steps.pop("attitude-cylinder", None)
else:
    steps["attitude-cylinder"] = {"image-fit": False}
m["steps"] = steps
json.dump(m, open(p, "w"), indent=1)
PY
  done
fi
echo "== $N $KIND trials of $DUR s in $ROOT ($made generated now); machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
export PATH=$BIN:$PATH
for pass in force again; do
  extra=""; [ "$pass" = force ] && extra=--force
  set +e
  "$SRC/scripts/rk-nightly" "$ROOT" -j "$JOBS" $PLOTS $extra -q --rk-run "$BIN/rk-run"
  rc=$?
  set -e
  python3 - "$ROOT/rk-nightly-summary.json" "$pass" "$rc" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
c = s["counts"]
print("-- pass %-5s exit %s: %d done, %d up to date, %d failed" % (sys.argv[2], sys.argv[3], c["done"], c["up_to_date"], c["failed"]))
print("   wall %.2f s; tools %.2f s (cpu %.2f s) on %d cores -> ideal %.2f s; wall / ideal = %.3f (target <= 1.10)"
      % (s["wall_s"], s["tool_time_s"], s["tool_cpu_s"], s["cores_used"], s.get("ideal_wall_s", 0.0), s.get("wall_over_ideal", 0.0)))
PY
done
if [ "$KIND" = theodolite ]; then
  python3 - "$ROOT" "$N" <<'PY'
import json, os, sys
root, n = sys.argv[1], int(sys.argv[2])
print("   per trial, step attitude-cylinder (last --force pass): wall_s, method, rows; image fit: seconds, fits, "
      "model evaluations, per frame")
tot = 0.0
for k in range(1, n + 1):
    name = "t%0*d" % (len(str(n)), k)
    rep = json.load(open(os.path.join(root, name, "out", "report.json")))
    for s in rep["steps"]:
        if s["kind"] != "attitude-cylinder":
            continue
        q = s.get("quality", {})
        f = q.get("image_fit", {})
        rows = q.get("rows", 0) or 1
        wall = s.get("time", {}).get("wall_s", 0.0)
        tot += wall
        print("   %s %s: %.2f s, %s, %d rows; fit %.2f s, %s fits, %s evaluations; %.3f s and %.0f evaluations per frame"
              % (name, s["id"], wall, q.get("method", "?"), rows, f.get("seconds", 0.0), f.get("fits", "-"),
                 f.get("model_evaluations", "-"), f.get("seconds", 0.0) / rows, f.get("model_evaluations", 0) / rows))
print("   attitude-cylinder: %.2f s over %d trials, %.2f s per trial" % (tot, n, tot / max(n, 1)))
PY
fi
[ "$PAGES" = 1 ] || { echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"; exit 0; }

# -- issue 19: report pages and index --------------------------------------------------------------------
NOPAGE=$ROOT/.bench-nopage; rm -rf "$NOPAGE"; mkdir -p "$NOPAGE"
for f in "$BIN"/rk-* "$BIN"/*.py; do ln -s "$f" "$NOPAGE/$(basename "$f")"; done
rm "$NOPAGE/rk-run" "$NOPAGE/rk-report"; cp "$BIN/rk-run" "$NOPAGE/rk-run"   # a copy: it looks beside itself
printf '#!/bin/sh\nexit 0\n' > "$NOPAGE/rk-report"; chmod +x "$NOPAGE/rk-report"
declare -A WALL=([nopage]=1e9 [pages]=1e9)
# Issue 34: the exports (export-kml, export-czml steps) count with the pages: the "nopage" passes switch them off
# in every trial's "steps", the "pages" passes on again.
exports() {
  for m in "$ROOT"/t*/trial.json; do
    python3 - "$m" "$1" <<'PY'
import json, sys
p, on = sys.argv[1], sys.argv[2] == "on"
m = json.load(open(p))
steps = m.get("steps") or {}
for k in ("export-kml", "export-czml"):
    if on:
        steps.pop(k, None)
    else:
        steps[k] = False
m["steps"] = steps
json.dump(m, open(p, "w"), indent=1)
PY
  done
}
for pass in nopage pages nopage pages; do   # alternated, the smaller wall of each kept: less load noise
  runner=$BIN/rk-run; [ "$pass" = nopage ] && runner=$NOPAGE/rk-run
  if [ "$pass" = nopage ]; then exports off; else exports on; fi
  find "$ROOT" -name report.html -path '*/out/*' -delete
  set +e; "$SRC/scripts/rk-nightly" "$ROOT" -j "$JOBS" $PLOTS --force -q --rk-run "$runner"; set -e
  w=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_s'])" "$ROOT/rk-nightly-summary.json")
  WALL[$pass]=$(python3 -c "print(min($w, ${WALL[$pass]}))")
  echo "-- pass $pass: wall $w s, pages: $(find "$ROOT" -name report.html -path '*/out/*' | wc -l), load $(cut -d' ' -f1 /proc/loadavg)"
done
index_s=$(grep -o 'index: .* ([0-9.]* s)' "$ROOT/rk-nightly.log" | tail -1 | grep -o '([0-9.]* s)' | tr -d '(s )')
pages_s=0
for d in "$ROOT"/t*/out; do
  s0=$(date +%s.%N); "$BIN/rk-report" "$d" --quiet; s1=$(date +%s.%N)
  pages_s=$(python3 -c "print($pages_s + $s1 - $s0)")
done
python3 - "${WALL[nopage]}" "${WALL[pages]}" "$pages_s" "$index_s" "$N" "$JOBS" "$ROOT" <<'PY'
import glob, os, sys
nopage, pages, pages_s, index_s, n, jobs, root = map(str, sys.argv[1:])
nopage, pages, pages_s, index_s = float(nopage), float(pages), float(pages_s), float(index_s or 0)
cores = min(int(jobs), int(n))
sizes = [os.path.getsize(p) for p in glob.glob(os.path.join(root, "t*/out/report.html"))]
print("   nightly wall without pages and exports %.2f s, with pages, index and exports %.2f s: +%.1f %% (target <= 10 %%)"
      % (nopage, pages, 100 * (pages - nopage) / nopage))
print("   pages made one by one: %.2f s for %s (%.2f s each; / %d cores = %.1f %% of the no-page nightly); "
      "index %.3f s" % (pages_s, n, pages_s / int(n), cores, 100 * pages_s / cores / nopage, index_s))
print("   page size: %.0f kB mean, %.0f kB max" % (sum(sizes) / len(sizes) / 1024, max(sizes) / 1024))
PY
# Render time of a 20-second beacon trial's page in Chromium.
R20=$ROOT/.bench-render20
if [ ! -s "$R20/trial.json" ]; then "$BIN/rk-sim" beacon --out "$R20" --force --preset small --duration 20 --seed 99 --quiet; fi
"$BIN/rk-run" "$R20" --force --quiet
python3 "$SRC/tests/cli/browser_check.py" "$R20/out/report.html" --repeat 5 || echo "(browser check failed or chromium missing)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
