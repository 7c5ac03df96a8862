#!/usr/bin/env bash
# rk-extract points end to end against decoding alone (issue 31: within 1.1 × decoding). rk-sim points' `moving`
# scene at 2448×2048 (FRAMES frames, FFV1 in Matroska as rk-sim writes it), once without clouds (every point in
# view) and once with them (two of the seven points hidden by a cloud for about 40 % of the frames, so that each
# frame also runs a whole-frame re-acquisition search for them); for each,
#   rk-extract beacon --video V --decode-only      (decoding: the same reader, ffmpeg beside it)
#   rk-extract points --video V --frames F --seeds S -o P   (the seven seeds of rk-sim's seeds.csv)
# median wall time of REPEATS runs each, and the ratio. Prints a Markdown table (also OUT/summary.md).
#   bench/points_end_to_end.sh [OUT]      needs a Release build in build/ (scripts/setup.sh)
# Environment: FRAMES (default 100), REPEATS (default 3).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${RK_BIN:-$ROOT/build/apps}
OUT=${1:-/tmp/rk-points-e2e-bench}
FRAMES=${FRAMES:-100}
REPEATS=${REPEATS:-3}
mkdir -p "$OUT"
S=$OUT/summary.md
: > "$S"
say() { echo "$*" | tee -a "$S"; }
. "$ROOT/bench/lib.sh"  # median, timed
say "## rk-extract points end to end (issue 31) — $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores"
say ""
say "rk-sim points moving, 2448x2048, $FRAMES frames, 7 points; median of $REPEATS runs; \`bench/points_end_to_end.sh\` (Release build)."
say ""
say "| scene | decoding alone (s) | rk-extract points (s) | ratio | rows ok / predicted / lost / reacquired |"
say "|---|---|---|---|---|"
for clouds in no yes; do
  d=$OUT/scene_$clouds
  extra=()
  [ "$clouds" = no ] && extra=(--no-clouds)
  [ -f "$d/video.mkv" ] || "$B/rk-sim" points --out "$d" --scenario moving --frames "$FRAMES" --width 2448 --height 2048 \
    --seed 3 --quiet "${extra[@]}"
  cat "$d/video.mkv" > /dev/null
  dec=$(timed "$B/rk-extract" beacon --video "$d/video.mkv" --decode-only --quiet)
  pts=$(timed "$B/rk-extract" points --video "$d/video.mkv" --frames "$d/frames.csv" --seeds "$d/seeds.csv" -o "$d/points.csv" --quiet)
  counts=$(awk -F, 'NR > 1 {n[$6]++} END {printf "%d / %d / %d / %d", n["ok"], n["predicted"], n["lost"], n["reacquired"]}' "$d/points.csv")
  say "| clouds: $clouds | $dec | $pts | $(awk -v a="$pts" -v b="$dec" 'BEGIN {printf "%.2f", a / b}') | $counts |"
done
