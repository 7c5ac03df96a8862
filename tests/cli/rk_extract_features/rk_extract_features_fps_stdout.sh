#!/usr/bin/env bash
# CLI test rk_extract_features_fps_stdout: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
rk-extract features --video "$d/att/video.mkv" --fps 10 --t0 1 --target "$d/target.json" -o - > "$data/att_points_fps.csv"
cmp "$data/att_points_fps.csv" "$data/att_points.csv"
echo ok
