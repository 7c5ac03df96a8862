#!/usr/bin/env bash
# CLI test rk_bad_rows_extract_features: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/att_small; w=$data/bad_rows/features; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$d/att/frames.csv" t_s)
skip_same "$w" frames "$n" -- rk-extract features --video "$d/att/video.mkv" --frames @frames.csv --target "$d/target.json"
echo ok
