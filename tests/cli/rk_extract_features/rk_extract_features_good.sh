#!/usr/bin/env bash
# CLI test rk_extract_features_good: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
rm -f "$data/att_points.csv" "$data/att_points.json"
out=$(rk-extract features --video "$d/att/video.mkv" --frames "$d/att/frames.csv" --target "$d/target.json" \
      -o "$data/att_points.csv" --report "$data/att_points.json")
test -z "$out"
test "$(head -n 1 "$data/att_points.csv")" = "frame,t_s,id,x_px,y_px,status,sigma_px,ncc,radius_px"
test "$(grep -c '' "$data/att_points.csv")" = 81
test "$(grep -c ',fin,,,lost,' "$data/att_points.csv")" = 3
test "$(grep -c ',fin,[0-9.]*,[0-9.]*,reacquired,' "$data/att_points.csv")" = 1
python3 "$src/bench/attitude_points_stats.py" "$data/att_points.csv" "$d/truth/points.csv" | tee "$data/att_points_stats.txt"
grep -q 'identity errors 0 ' "$data/att_points_stats.txt"
awk '/rms/ { if ($7 > 0.05 || $14 > 0.05) exit 1 }' "$data/att_points_stats.txt"
grep -q '"ok": 1' "$data/att_points.json"
grep -q '"frames_with_4_points": 10' "$data/att_points.json"
echo ok
