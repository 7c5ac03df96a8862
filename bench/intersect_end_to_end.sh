#!/usr/bin/env bash
# rk-intersect end to end on a 10-minute three-station 20 Hz trial (issue 18 target: read, align, intersect,
# smooth, write ≤ 2 s): the real binary from files to file, REPEAT times each without and with --smooth; prints
# every wall and user time and the median. Rows: the union of the stations' frame times (20, 25, 16 Hz).
#   bench/intersect_end_to_end.sh [OUT]     needs a Release build with rk-sim and rk-intersect
# Environment: BIN (default <repo>/build-rel/apps), REPEAT (5), DURATION (600).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${BIN:-$ROOT/build-rel/apps}
OUT=${1:-/tmp/rk-intersect-e2e}
REPEAT=${REPEAT:-5}
DURATION=${DURATION:-600}
for tool in rk-sim rk-intersect; do
  [ -x "$BIN/$tool" ] || { echo "intersect_end_to_end.sh: error: $BIN/$tool not built (set BIN)" >&2; exit 1; }
done
"$BIN/rk-sim" multistation --out "$OUT/trial" --force --stations 3 --duration "$DURATION" --rate 20 \
  --path crossing --seed 9 --quiet
for smooth in "" "--smooth"; do
  walls=()
  for i in $(seq 1 "$REPEAT"); do
    t=$( { /usr/bin/time -f '%e %U' "$BIN/rk-intersect" --stations "$OUT/trial/stations.json" \
             -o "$OUT/traj.csv" $smooth --quiet; } 2>&1 )
    echo "rk-intersect ${smooth:-(no --smooth)} run $i: wall ${t% *} s, user ${t#* } s"
    walls+=("${t% *}")
  done
  rows=$(($(grep -vc '^#' "$OUT/traj.csv") - 1))
  med=$(printf '%s\n' "${walls[@]}" | sort -g | sed -n "$(((REPEAT + 1) / 2))p")
  echo "rk-intersect ${smooth:-(no --smooth)}: $rows rows, median wall $med s over $REPEAT runs"
done
