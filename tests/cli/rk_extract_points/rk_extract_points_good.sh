#!/usr/bin/env bash
# CLI test rk_extract_points_good: registered, and described, in tests/cli/rk_extract_points.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/points_small; rm -rf "$d"
rk-sim points --out "$d" --scenario reversal --frames 100 --seed 11 --quiet
rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" --seeds "$d/seeds.csv" -o "$d/points.csv" \
  --report "$d/points.json" --quiet
test "$(head -n 1 "$d/points.csv")" = "frame,t_s,id,x_px,y_px,status,sigma_x_px,sigma_y_px,score"
python3 "$src/tests/cli/rk_extract_points/score_points.py" "$d/points.csv" "$d/truth/points.csv" "$d/points.json"
echo ok
