#!/usr/bin/env bash
# CLI test rk_bad_rows_extract: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/extract; w=$data/bad_rows/extract; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$d/frames.csv" frame)
skip_same "$w" frames "$n" -- rk-extract beacon --video "$d/beacon.mkv" --frames @frames.csv
rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames.csv" -o "$w/skip2.csv" --bad-rows skip 2> "$w/err"
test "$(grep -c 'skipped bad row' "$w/err")" = "$n"
"$expect" 3 "$w/x.csv" 'frames.csv:4:[0-9]+:' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames.csv" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$d/frames_text.csv" -- rk-extract beacon --video "$d/beacon.mkv" --frames "$d/frames_text.csv" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-extract beacon --video "$d/beacon.mkv" --frames "$d/frames.csv" -o "$w/x.csv" --bogus --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-extract --report "$w/r4.json" beacon --video "$w/no_such.mkv" --fps 20 -o "$w/x.csv"
echo ok
