#!/usr/bin/env bash
# CLI test rk_register_bad_input: registered, and described, in tests/cli/rk_register.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/radar3; o=$data/register_bad; rm -rf "$o"; mkdir -p "$o"
P=$d/plots.csv; N=$d/nav.csv; x=$o/x.csv
# Plots without nav at their time: nav stops at t = 200 s.
awk -F, 'NR == 1 || $1 + 0 <= 200' "$N" > "$o/nav_short.csv"
$expect 3 "$x" 'plots.csv:[0-9]+:1: .*no nav of radar .a. at t_s = 205' -- rk-register bernoulli --plots "$P" --nav "$o/nav_short.csv" -o "$x"
# One radar missing from the plots.
grep -v ',b,' "$P" > "$o/only_a.csv"
$expect 3 "$x" "only_a.csv: no plots of radar 'b'" -- rk-register bernoulli --plots "$o/only_a.csv" --nav "$N" -o "$x"
# Unknown radar name (line 5 renamed).
awk -F, 'BEGIN{OFS=","} NR == 5 {$2 = "c"} {print}' "$P" > "$o/radar_c.csv"
$expect 3 "$x" "radar_c.csv:5:[0-9]+: .*unknown radar 'c'" -- rk-register kf --plots "$o/radar_c.csv" --nav "$N" -o "$x"
# A third radar in the nav.
(cat "$N"; echo '400,c,25,110,0,0,0,0') > "$o/nav3.csv"
$expect 3 "$x" "nav3.csv:162:[0-9]+: .*third radar 'c'" -- rk-register batch --plots "$P" --nav "$o/nav3.csv" -o "$x"
# NaN value.
awk -F, 'BEGIN{OFS=","} NR == 7 {$4 = "NaN"} {print}' "$P" > "$o/nan.csv"
$expect 3 "$x" 'nan.csv:7:[0-9]+: .*not a finite number' -- rk-register bernoulli --plots "$o/nan.csv" --nav "$N" -o "$x"
# Times out of order (lines 30 and 200 swapped).
awk 'NR == FNR {l[FNR] = $0; next} FNR == 30 {print l[200]; next} FNR == 200 {print l[30]; next} {print}' "$P" "$P" > "$o/order.csv"
$expect 3 "$x" 'order.csv:(30|31):1: .*backwards' -- rk-register bernoulli --plots "$o/order.csv" --nav "$N" -o "$x"
# kf without track_id.
cut -d, -f1-5 "$P" > "$o/no_id.csv"
$expect 3 "$x" "no_id.csv:1:1: .*track_id" -- rk-register kf --plots "$o/no_id.csv" --nav "$N" -o "$x"
$expect 3 "$x" "no_id.csv:1:1: .*track_id" -- rk-register batch --associate track --plots "$o/no_id.csv" --nav "$N" -o "$x"
rk-register bernoulli --plots "$o/no_id.csv" --nav "$N" -o "$o/ok.csv"   # bernoulli does not need it
# Usage errors (2), I/O errors (4), output never replaces an input.
$expect 2 "$x" 'linearize' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$x" --linearize paper
$expect 2 "$x" 'subset-length must be in \[1, 32\]' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$x" -L 0
$expect 2 "$x" 'p0: give six values' -- rk-register kf --plots "$P" --nav "$N" -o "$x" --p0 1,2,3,4,5
$expect 2 "$x" 'no plot has this track_id' -- rk-register kf --plots "$P" --nav "$N" -o "$x" --track 9
$expect 2 "$x" 'only one input can be read from stdin' -- rk-register kf --plots - --nav - -o "$x"
$expect 2 "$x" 'subcommand' -- rk-register --plots "$P" --nav "$N" -o "$x"
$expect 4 "$x" 'nothere.csv' -- rk-register bernoulli --plots "$o/nothere.csv" --nav "$N" -o "$x"
$expect 4 - '' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$o/nodir/x.csv"
cp "$P" "$o/same.csv"
$expect 2 - 'input' -- rk-register bernoulli --plots "$o/same.csv" --nav "$N" -o "$o/same.csv"
cmp "$o/same.csv" "$P"
echo ok
