#!/usr/bin/env bash
# CLI test rk_attitude_oi_row_status: registered, and described, in tests/cli/rk_attitude_oi.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
awk -F, 'NR == 1 || $1 < 1.25 || $1 > 1.45' "$d/turret.csv" > "$data/att_turret_gap.csv"
awk -F, 'NR == 1 || $1 != 7 || $3 == "nose" || $3 == "tail" || $3 == "lwing"' "$d/truth/points.csv" > "$data/att_pts3.csv"
rk-attitude oi --points "$data/att_pts3.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$data/att_turret_gap.csv" -o "$data/att_pose_gap.csv" --quiet
grep -q '^3,1.300000000,,,,,,,invalid,.*,turret,,$' "$data/att_pose_gap.csv"
grep -q '^7,1.700000000,,,,,,,lost,,,3,.*,few_points,' "$data/att_pose_gap.csv"
grep -q '^8,1.800000000,.*,reacquired,' "$data/att_pose_gap.csv"
# The warning names the turret log.
rk-attitude oi --points "$data/att_pts3.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$data/att_turret_gap.csv" -o "$data/att_pose_gap_warn.csv" 2>&1 | grep -q 'warning: 2 of 10 frame times are not covered by'
echo ok
