#!/usr/bin/env bash
# CLI test rk_analyze_bad_input: registered, and described, in tests/cli/rk_analyze.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/analyze; o=$d/bad.json; rm -f "$o"
L() { "$expect" "$@"; }
L 3 "$o" 'ref_noaz.csv:1:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref_noaz.csv" --columns az_deg -o "$o"
L 3 "$o" 'est.csv:1:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns yaw_deg -o "$o"
L 3 "$o" 'est_text.csv:2:[0-9]+:' -- rk-analyze compare --estimate "$d/est_text.csv" --reference "$d/ref.csv" --columns range_m -o "$o"
L 3 "$o" 'est_nan.csv:2:[0-9]+:' -- rk-analyze compare --estimate "$d/est_nan.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 3 "$o" 'ref_back.csv:3:[0-9]+:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref_back.csv" --columns az_deg -o "$o"
L 4 "$o" 'no_such.csv' -- rk-analyze compare --estimate "$d/no_such.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --bogus
L 2 "$o" -- rk-analyze --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --after 5 --before 1
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --interp quintic
L 2 - 'refusing to overwrite' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$d/ref.csv"
grep -q '^t_s,az_deg,range_m' "$d/ref.csv"
echo ok
