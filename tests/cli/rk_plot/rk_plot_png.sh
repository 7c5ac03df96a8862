#!/usr/bin/env bash
# CLI test rk_plot_png: registered, and described, in tests/cli/rk_plot.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
plot=$src/scripts/rk-plot
d=$data/plot; rm -rf "$d"; mkdir -p "$d"
printf '# comment\nt_s,az_deg,range_m,status\n0,1.0,10,ok\n# mid comment\n0.1,1.1,,lost\n0.2,1.3,10.2,ok\n' > "$d/a.csv"
printf 't_s,range_m,az_deg\n0,10.1,0.9\n0.2,10.3,1.2\n' > "$d/b.csv"
"$plot" -i "$d/a.csv" -i "$d/b.csv" --columns az_deg,range_m --title 'test' -o "$d/out.png"
test "$(od -An -tx1 -N8 "$d/out.png" | tr -d ' \n')" = 89504e470d0a1a0a
test -z "$(ls -A "$d" | grep '^\.rk-plot-' || true)"   # no temporary left behind
"$plot" -i - --columns range_m --x t_s -o - < "$d/a.csv" > "$d/stdout.png"
test "$(od -An -tx1 -N4 "$d/stdout.png" | tr -d ' \n')" = 89504e47
# An azimuth crossing north: no line across the plot at the wrap. Drawn exactly as the same rows with a gap
# (an empty az_deg) halfway between the two rows of the wrap: the points stay, the line between them does not.
printf 't_s,az_deg\n0,359.0\n0.1,359.5\n0.2,0.1\n0.3,0.6\n' > "$d/north.csv"
printf 't_s,az_deg\n0,359.0\n0.1,359.5\n0.15,\n0.2,0.1\n0.3,0.6\n' > "$d/north_gap.csv"
"$plot" -i "$d/north.csv" --columns az_deg -o "$d/north.png"
"$plot" -i "$d/north_gap.csv" --columns az_deg -o "$d/north_gap.png"
cmp "$d/north.png" "$d/north_gap.png"
# ... and a column that does not wrap (range_m) keeps its line across the same jump.
sed 's/az_deg/range_m/' "$d/north.csv" > "$d/jump.csv"; sed 's/az_deg/range_m/' "$d/north_gap.csv" > "$d/jump_gap.csv"
"$plot" -i "$d/jump.csv" --columns range_m -o "$d/jump.png"
"$plot" -i "$d/jump_gap.csv" --columns range_m -o "$d/jump_gap.png"
! cmp -s "$d/jump.png" "$d/jump_gap.png"
echo ok
