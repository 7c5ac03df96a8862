#!/usr/bin/env bash
# CLI test rk_attitude_cylinder_row_status: registered, and described, in tests/cli/rk_attitude_cylinder.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/att_cyl; mkdir -p "$W"
grep -v '^2,.*,tail2,' "$T/points.csv" > "$W/p_miss.csv"
awk -F, 'NR == 1 || $1 < 0.93 || $1 > 1.17' "$T/theodolite.csv" > "$W/theo_gap.csv"   # 0.26 s gap > 0.2 s
rk-attitude cylinder --points "$W/p_miss.csv" --theodolite "$W/theo_gap.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" -o "$W/axis_status.csv" 2> "$W/err.txt"
grep -q 'warning: 3 frame(s) invalid (no_theodolite 3' "$W/err.txt"
awk -F, 'NR > 1 { print $1, $5, $8, ($3 == "" ? "empty" : "value") }' "$W/axis_status.csv" > "$W/st.txt"
grep -q '^2 lost missing_points empty$' "$W/st.txt"
grep -q '^3 invalid no_theodolite empty$' "$W/st.txt"
grep -q '^1 invalid no_theodolite empty$' "$W/st.txt"
grep -q '^4 ok ambiguous value$' "$W/st.txt"   # first row after the gap: no history
echo ok
