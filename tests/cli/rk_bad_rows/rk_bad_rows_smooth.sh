#!/usr/bin/env bash
# CLI test rk_bad_rows_smooth: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/aukf; w=$data/bad_rows/smooth; rm -rf "$w"; mkdir -p "$w"
n=$(dirty "$d/in.csv" "$w/in.csv" yaw_deg)
awk 'BEGIN { print "t_s,frame"; for (k = 0; k < 12; k++) printf "%.3f,%d\n", 0.25 * k, k }' > "$w/at_clean.csv"
na=$(dirty "$w/at_clean.csv" "$w/at.csv" frame)
for sub in aukf singer resample; do
  extra=(); [ $sub = resample ] && extra=(--rate 10)
  rk-smooth $sub -i "$d/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/$sub.clean.csv" -q
  rk-smooth $sub -i "$w/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/$sub.skip.csv" --bad-rows skip --report "$w/$sub.json" -q
  cmp "$w/$sub.clean.csv" "$w/$sub.skip.csv"
  report_ok "$w/$sub.json" input "$n"
  "$expect" 3 "$w/x.csv" 'in.csv:4:[0-9]+:' -- rk-smooth $sub -i "$w/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/x.csv"
done
# resample --at: its own bad rows too ("frame" is copied through, so "abc" there is not a bad row).
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at_clean.csv" -o "$w/at.clean.csv" -q
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at.csv" -o "$w/at.skip.csv" --bad-rows skip --report "$w/at.json" -q
awk -F, 'NF == 2 && $1 != "nan" && $1 !~ /^-/' "$w/at.csv" > "$w/at_kept.csv"   # the 4 bad rows out, abc/inf kept
test "$(grep -c '' "$w/at_kept.csv")" = 15
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at_kept.csv" -o "$w/at.kept.csv" -q
cmp "$w/at.kept.csv" "$w/at.skip.csv"
report_ok "$w/at.json" at $((na - 2))
fails 3 "$w/r3.json" "$w/x.csv" "$d/text.csv" -- rk-smooth aukf -i "$d/text.csv" --columns yaw_deg -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-smooth aukf -i "$d/in.csv" -o "$w/x.csv" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-smooth singer -i "$w/no_such.csv" --columns yaw_deg -o "$w/x.csv" --report "$w/r4.json"
echo ok
