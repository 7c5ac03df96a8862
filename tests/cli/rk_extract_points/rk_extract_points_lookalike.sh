#!/usr/bin/env bash
# CLI test rk_extract_points_lookalike: registered, and described, in tests/cli/rk_extract_points.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/points_lookalike; rm -rf "$d"
rk-sim points --out "$d" --scenario lookalike --frames 120 --seed 4 --quiet
rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" --seeds "$d/seeds.csv" -o "$d/points.csv" \
  --report "$d/points.json" --quiet
python3 "$src/tests/cli/rk_extract_points/score_points.py" "$d/points.csv" "$d/truth/points.csv" "$d/points.json" \
  --lookalike
echo ok
