#!/usr/bin/env bash
# CLI test rk_bad_rows_frames_forms: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/extract; w=$data/bad_rows/frames_forms; rm -rf "$w"; mkdir -p "$w"
x() { rk-extract beacon -q --video "$d/beacon.mkv" "$@"; }
x --frames "$d/frames.csv" -o "$w/clean.csv"
rows=$(grep -vc '^#' "$w/clean.csv")

# Issue 27 item 13: one backwards t_s (frame 5, line 7). --bad-rows skip drops that row and frame 5 is a
# hole: decoded, not measured, one warning; every other frame as in the clean run's row count.
awk -F, 'NR == 7 { printf "%s,%.6f\n", $1, $2 - 1; next } { print }' "$d/frames.csv" > "$w/frames_back.csv"
rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames_back.csv" -o "$w/hole.csv" --bad-rows skip 2> "$w/hole.err"
cat "$w/hole.err"
grep -q 'frames_back.csv:7:[0-9]*: skipped bad row' "$w/hole.err"
grep -q 'frames_back.csv: 1 frames have no time' "$w/hole.err"
test "$(grep -vc '^#' "$w/hole.csv")" = "$((rows - 1))"
if grep -q '^5,' "$w/hole.csv"; then echo "FAIL: frame 5 measured without a time"; exit 1; fi
"$expect" 3 "$w/x.csv" 'frames_back.csv:7:[0-9]+:' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames_back.csv" -o "$w/x.csv"
# A frame number wrong for another reason (3 after 1, nothing skipped) stays an error under skip.
awk -F, 'NR == 4 { print 3 "," $2; next } { print }' "$d/frames.csv" > "$w/frames_gap.csv"
"$expect" 3 "$w/x.csv" 'frames_gap.csv:4:1:.*expected 2, found 3' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames_gap.csv" -o "$w/x.csv" --bad-rows skip

# Item 14: frame numbers as pandas writes them (+0, 1.0, 2e0), a UTF-8 byte-order mark and quoted fields
# (one with a newline inside, in an extra column) give the clean output byte for byte.
awk -F, 'NR == 1 { printf "\357\273\277%s,note\n", $0; next }
         NR == 2 { printf "+0,\"%s\",\"a, \"\"b\"\"\"\n", $2; next }
         NR == 3 { printf "1.0,%s,\"two\nlines\"\n", $2; next }
         NR == 4 { printf "2e0,%s,\n", $2; next } { print $0 "," }' "$d/frames.csv" > "$w/frames_pandas.csv"
x --frames "$w/frames_pandas.csv" -o "$w/pandas.csv"
cmp "$w/clean.csv" "$w/pandas.csv"
# The line after the quoted newline keeps its own number in messages.
awk 'NR == 6 { sub(/,[^,]*,$/, ",abc,") } { print }' "$w/frames_pandas.csv" > "$w/frames_pandas_bad.csv"
grep -q '^3,abc,$' "$w/frames_pandas_bad.csv"
"$expect" 3 "$w/x.csv" 'frames_pandas_bad.csv:6:3: column .t_s.' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames_pandas_bad.csv" -o "$w/x.csv"

# UTF-16 (as Windows tools save "Unicode text"): named as such, exit 3.
python3 -c 'import sys; open(sys.argv[2], "wb").write(open(sys.argv[1]).read().encode("utf-16"))' "$d/frames.csv" "$w/frames_utf16.csv"
"$expect" 3 "$w/x.csv" 'frames_utf16.csv: not UTF-8 text \(UTF-16\?\)$' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames_utf16.csv" -o "$w/x.csv"
echo ok
