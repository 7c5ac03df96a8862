#!/usr/bin/env bash
# Re-acquisition after an occlusion during which the beacon's image motion reverses (issue 15 item 2).
#   bench/beacon_reacquire.sh [OUT] [BEFORE_RK_EXTRACT]
# For each occlusion length and seed: rk-sim beacon --preset small --duration 5 --servo-hold 1.5:0.4
# (the turret stops for 0.4 s, then catches up: the image motion reverses at 1.9 s) --occlusion 1.7:L
# --distractors 2, then rk-extract beacon (build/apps, and BEFORE_RK_EXTRACT when given: a binary of the
# code before the fix), scored by bench/beacon_track_stats.py: frames from the beacon's return to the first
# good measurement (0 = the very first frame back) and frames with a position off the beacon.
# Needs a Release build in build/. Writes OUT (default /tmp/rk-beacon-reacq); prints a Markdown table.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=$ROOT/build/apps
OUT=${1:-/tmp/rk-beacon-reacq}
BEFORE=${2:-}
SEEDS=${SEEDS:-"1 2 3 4 5"}
LENGTHS=${LENGTHS:-"0.25 0.5 1 2"}
mkdir -p "$OUT"
jget() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
# "delays (max), false frames" of one track.
score() {
  python3 "$ROOT/bench/beacon_track_stats.py" "$1" "$2" > "$1.stats.json"
  jget "$1.stats.json" "'%s | %d' % (d['reacquire_delays'], d['false_frames'])"
}
if [ -n "$BEFORE" ]; then
  echo "| occlusion | seed | before: frames to re-acquire | before: false frames | after: frames to re-acquire | after: false frames |"
  echo "|---|---|---|---|---|---|"
else
  echo "| occlusion | seed | frames to re-acquire | false frames |"
  echo "|---|---|---|---|"
fi
for len in $LENGTHS; do
  for seed in $SEEDS; do
    d=$OUT/occ${len}_s$seed
    "$B/rk-sim" beacon --out "$d" --force --preset small --duration 5 --seed "$seed" --servo-hold 1.5:0.4 \
      --occlusion "1.7:$len" --distractors 2 --quiet
    args=(beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" --quiet)
    "$B/rk-extract" "${args[@]}" -o "$d/after.csv"
    row="| $len s | $seed |"
    if [ -n "$BEFORE" ]; then
      "$BEFORE" "${args[@]}" -o "$d/before.csv"
      row="$row $(score "$d/before.csv" "$d/truth/beacon.csv") |"
    fi
    echo "$row $(score "$d/after.csv" "$d/truth/beacon.csv") |"
  done
done
