#!/usr/bin/env bash
# CLI test rk_plot_bad_input: registered, and described, in tests/cli/rk_plot.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
plot=$src/scripts/rk-plot
d=$data/plot; o=$d/bad.png; rm -f "$o"
printf 't_s,a_m\n0,1\n1,x\n' > "$d/text.csv"
printf 't_s,a_m\n0,1\n1,2,3\n' > "$d/fields.csv"
L() { "$expect" "$@"; }
L 3 "$o" 'text.csv:3:3:' -- "$plot" -i "$d/text.csv" --columns a_m -o "$o"
L 3 "$o" 'fields.csv:3:' -- "$plot" -i "$d/fields.csv" --columns a_m -o "$o"
L 3 "$o" 'a.csv:2:' -- "$plot" -i "$d/a.csv" --columns nope_m -o "$o"
L 4 "$o" 'no_such.csv' -- "$plot" -i "$d/no_such.csv" --columns a_m -o "$o"
L 2 "$o" -- "$plot" -i "$d/a.csv" --columns az_deg -o "$o" --bogus
L 2 "$o" -- "$plot" -i "$d/a.csv" -o "$o"
L 2 - 'refusing to overwrite' -- "$plot" -i "$d/a.csv" --columns az_deg -o "$d/a.csv"
echo ok
