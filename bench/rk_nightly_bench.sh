#!/usr/bin/env bash
# Issue 7 target: reprocessing 20 sample trials on this machine takes a total wall time within 10 % of
# (sum of the tools' own times) / (cores used). Generates N small beacon trials with rk-sim (kept between
# runs in ROOT; --regen makes them anew), runs `rk-nightly ROOT --force -j JOBS` and prints, from its
# summary, the wall time, the sum of the tool times (each step's wall time measured by rk-run around the
# child process), the ideal wall time tools / cores and their ratio; then a second rk-nightly run, where
# every trial is up to date.
#   bench/rk_nightly_bench.sh [--trials N] [--duration S] [--jobs J] [--no-plots] [--root DIR] [--regen]
# Defaults: 20 trials, 10 s each (200 frames of 640x512, FFV1), J = nproc, plots on, ROOT=/tmp/rk-nightly-bench.
set -euo pipefail
SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${RK_BIN:-$SRC/build/apps}
N=20; DUR=10; JOBS=$(nproc); PLOTS=""; ROOT=/tmp/rk-nightly-bench; REGEN=0
while [ $# -gt 0 ]; do
  case "$1" in
    --trials) N=$2; shift 2 ;;
    --duration) DUR=$2; shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --no-plots) PLOTS=--no-plots; shift ;;
    --root) ROOT=$2; shift 2 ;;
    --regen) REGEN=1; shift ;;
    *) echo "rk_nightly_bench.sh: error: unknown option $1" >&2; exit 2 ;;
  esac
done
[ "$REGEN" = 1 ] && rm -rf "$ROOT"
mkdir -p "$ROOT"
made=0
for k in $(seq -w 1 "$N"); do
  if [ ! -s "$ROOT/t$k/trial.json" ]; then
    "$BIN/rk-sim" beacon --out "$ROOT/t$k" --force --preset small --duration "$DUR" --seed "$((10#$k))" --quiet &
    made=$((made + 1))
    if [ $((made % JOBS)) = 0 ]; then wait; fi
  fi
done
wait
echo "== $N trials of $DUR s in $ROOT ($made generated now); machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
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
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
