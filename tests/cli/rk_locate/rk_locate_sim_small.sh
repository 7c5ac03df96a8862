#!/usr/bin/env bash
# CLI test rk_locate_sim_small: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
s=$data/small; o=$data/locate_e2e; rm -rf "$o"; mkdir -p "$o"
rk-locate --track "$s/truth/beacon.csv" --camera "$s/az/camera.json" --turret "$s/truth/turret.csv" \
  --range "$s/range.csv" -o "$o/located_true_turret.csv" -q
rk-locate --track "$s/truth/beacon.csv" --camera "$s/az/camera.json" --turret "$s/turret.csv" \
  --range "$s/range.csv" -o "$o/located.csv" -q
rk-analyze compare --estimate "$o/located_true_turret.csv" --reference "$s/truth/target.csv" \
  --columns az_deg,el_deg,range_m --arcsec -o "$o/stats_true_turret.json" -q
rk-analyze compare --estimate "$o/located.csv" --reference "$s/truth/target.csv" \
  --columns az_deg,el_deg,range_m --arcsec -o "$o/stats.json" -q
check() {  # file column key max
  awk -v c="\"$2\"" -v k="\"$3\"" -v m="$4" '
    index($0, c ": {") { inside = 1 }
    inside && index($0, k ":") { v = $0; sub(/.*: /, "", v); sub(/,$/, "", v);
      if (v == "null" || v + 0 > m + 0) { print FILENAME ": " c " " k " = " v " > " m; exit 1 } found = 1; exit 0 }
    END { if (!found) exit 1 }' "$1"
}
check "$o/stats_true_turret.json" az_deg rms 0.05
check "$o/stats_true_turret.json" el_deg rms 0.05
check "$o/stats.json" az_deg rms 5
check "$o/stats.json" el_deg rms 5
check "$o/stats.json" range_m rms 0.001
grep -q ',lost,' "$o/located.csv"   # occluded frames (empty truth pixels) kept as lost rows
echo ok
