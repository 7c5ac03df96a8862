#!/usr/bin/env bash
# CLI test rk_sim_posetrack_head: registered, and described, in tests/cli/rk_sim_posetrack.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/posetrack_head; rm -rf "$d"; mkdir -p "$d"
rk-sim posetrack --out "$d/a" --scenario head --duration 10 --seed 3 --dropout 0.1 --quiet
rk-sim posetrack --out "$d/b" --scenario head --duration 10 --seed 3 --dropout 0.1 --quiet
rk-sim posetrack --out "$d/c" --scenario head --duration 10 --seed 4 --dropout 0.1 --quiet
diff -r "$d/a" "$d/b"
if cmp -s "$d/a/measurements.csv" "$d/c/measurements.csv"; then echo "seed has no effect"; exit 1; fi
test "$(grep -c '' "$d/a/measurements.csv")" = 202
grep -q '^[0-9.]*,,,,,,$' "$d/a/measurements.csv"     # a dropped row keeps its time
# yaw column (6): all in [0, 360), both near 0 and near 360 (crosses north).
awk -F, 'NR > 1 { if ($6 < 0 || $6 >= 360) bad = 1; if ($6 < 90) lo = 1; if ($6 > 270) hi = 1 }
         END { exit !(lo && hi && !bad) }' "$d/a/truth.csv"
echo ok
