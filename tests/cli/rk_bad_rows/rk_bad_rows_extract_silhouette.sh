#!/usr/bin/env bash
# CLI test rk_bad_rows_extract_silhouette: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
T=$data/theo_trial; w=$data/bad_rows/silhouette; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$T/theo/frames.csv" t_s)
skip_same "$w" frames "$n" -- rk-extract silhouette --video "$T/theo/%06d.png" --frames @frames.csv
echo ok
