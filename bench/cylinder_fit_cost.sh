#!/usr/bin/env bash
# Issue 20: what the image fit costs per frame on a short seed 004 trial, and what it gives. Simulates one
# rk-sim theodolite trial (1536x1536 frames, the target ≈ 300 px at 1132 m; PNG), extracts the silhouette
# points, then runs rk-attitude cylinder without and with --video and prints, from --report, the image fit's
# seconds, fits and model evaluations per frame (evaluations are deterministic: comparable between builds and
# machines) and each run's yaw/pitch RMS error against the truth (rk-analyze compare).
#   bench/cylinder_fit_cost.sh [--bin DIR] [--duration S] [--seed N] [--work DIR] [--speed-mps V] [--el-deg E]
# Defaults: build/apps, 1 s (21 frames), seed 1, /tmp/rk-cylinder-fit-cost, 100 m/s, el 16.274 (seed 004).
# Compare two builds with RK_BIN_B: the same trial through the second build's rk-attitude.
set -euo pipefail
SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${RK_BIN:-$SRC/build/apps}; DUR=1; SEED=1; WORK=/tmp/rk-cylinder-fit-cost; SPEED=100; EL=16.274
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) BIN=$2; shift 2 ;;
    --duration) DUR=$2; shift 2 ;;
    --seed) SEED=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    --speed-mps) SPEED=$2; shift 2 ;;
    --el-deg) EL=$2; shift 2 ;;
    *) echo "cylinder_fit_cost.sh: error: unknown option $1" >&2; exit 2 ;;
  esac
done
rm -rf "$WORK"; mkdir -p "$WORK"; t=$WORK/trial
"$BIN/rk-sim" theodolite --out "$t" --images png --duration "$DUR" --speed-mps "$SPEED" --el-deg "$EL" \
  --seed "$SEED" --quiet
"$BIN/rk-extract" silhouette --video "$t/theo/%06d.png" --frames "$t/theo/frames.csv" -o "$WORK/points.csv" --quiet
run() {  # NAME BIN [rk-attitude args]
  local name=$1 bin=$2; shift 2
  local t0; t0=$(date +%s.%N)
  "$bin/rk-attitude" cylinder --points "$WORK/points.csv" --theodolite "$t/theodolite.csv" --camera "$t/theo/camera.json" \
    --target "$t/target.json" -o "$WORK/$name.csv" --report "$WORK/$name.json" --quiet "$@"
  local t1; t1=$(date +%s.%N)
  "$BIN/rk-analyze" compare --estimate "$WORK/$name.csv" --reference "$t/truth/axis.csv" --columns yaw_deg,pitch_deg \
    -o "$WORK/$name.stats.json" --quiet
  python3 - "$WORK/$name.json" "$WORK/$name.stats.json" "$name" "$t0" "$t1" <<'PY'
import json, sys
rep, st, name, t0, t1 = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
s = rep["summary"]; rows = s["rows"]; f = s.get("image_fit")
c = st["columns"]
line = "%-12s %3d frames, wall %6.2f s; yaw rms %.4f deg, pitch rms %.4f deg" % (
    name, rows, t1 - t0, c["yaw_deg"]["rms"], c["pitch_deg"]["rms"])
if f:
    line += "; fit %.2f s = %.3f s/frame, %s fits, %d evaluations = %.1f/frame" % (
        f["seconds"], f["seconds"] / rows, f.get("fits", "?"), f["model_evaluations"], f["model_evaluations"] / rows)
print(line)
PY
}
run three-point "$BIN"
run image-fit "$BIN" --video "$t/theo/%06d.png"
if [ -n "${RK_BIN_B:-}" ]; then run image-fit-B "$RK_BIN_B" --video "$t/theo/%06d.png"; fi
