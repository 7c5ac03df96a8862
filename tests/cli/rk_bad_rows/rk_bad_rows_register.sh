#!/usr/bin/env bash
# CLI test rk_bad_rows_register: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/radar3; w=$data/bad_rows/register; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$d/plots.csv" az_deg)
nn=$(dirty_in "$w" "$d/nav.csv" yaw_deg)
skip_same "$w" plots "$np" nav "$nn" -- rk-register kf --plots @plots.csv --nav @nav.csv
"$expect" 3 "$w/x.csv" 'nav.csv:[0-9]+:[0-9]+:' -- rk-register kf --plots "$d/plots.csv" --nav "$w/nav.csv" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$w/plots.csv" -- rk-register bernoulli --plots "$w/plots.csv" --nav "$d/nav.csv" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-register kf --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$w/x.csv" --bogus --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-register batch --plots "$d/plots.csv" --nav "$w/no_such.csv" -o "$w/x.csv" --report "$w/r4.json"
echo ok
