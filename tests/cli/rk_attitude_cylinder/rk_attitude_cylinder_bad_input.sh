#!/usr/bin/env bash
# CLI test rk_attitude_cylinder_bad_input: registered, and described, in tests/cli/rk_attitude_cylinder.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/att_cyl; mkdir -p "$W"
o=$W/bad.csv; rm -f "$o"
args=(--theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" --target "$T/target.json" -o "$o")
sed '3s/tail1/fin/' "$T/points.csv" > "$W/p_id.csv"
"$expect" 3 "$o" 'p_id.csv:3:[0-9]+: .*unknown point id' -- rk-attitude cylinder --points "$W/p_id.csv" "${args[@]}"
cut -d, -f1-4 "$T/points.csv" > "$W/p_col.csv"
"$expect" 3 "$o" 'p_col.csv.*y_px' -- rk-attitude cylinder --points "$W/p_col.csv" "${args[@]}"
sed '5s/,[0-9.]*$/,abc/' "$T/points.csv" > "$W/p_text.csv"
"$expect" 3 "$o" 'p_text.csv:5:' -- rk-attitude cylinder --points "$W/p_text.csv" "${args[@]}"
sed '2s/^0,1.000000000/0,9.000000000/' "$T/points.csv" > "$W/p_time.csv"
"$expect" 3 "$o" 'p_time.csv' -- rk-attitude cylinder --points "$W/p_time.csv" "${args[@]}"
grep -v tail2 "$T/points.csv" > "$W/p_two.csv"
"$expect" 1 "$o" 'no frame .* has all three points' -- rk-attitude cylinder --points "$W/p_two.csv" "${args[@]}"
awk -F, 'NR == 1 { print; next } { printf "%.9f,%s,%s\n", $1 + 100, $2, $3 }' "$T/theodolite.csv" > "$W/theo_late.csv"
"$expect" 3 "$o" 'theo_late.csv.*covers' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$W/theo_late.csv" \
  --camera "$T/theo/camera.json" --target "$T/target.json" -o "$o"
sed '4s/,[0-9.]*,/,north,/' "$T/theodolite.csv" > "$W/theo_text.csv"
"$expect" 3 "$o" 'theo_text.csv:4:' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$W/theo_text.csv" \
  --camera "$T/theo/camera.json" --target "$T/target.json" -o "$o"
echo '{"length_m": -2.5, "diameter_m": 0.25}' > "$W/t_neg.json"
"$expect" 3 "$o" 't_neg.json' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" \
  --camera "$T/theo/camera.json" --target "$W/t_neg.json" -o "$o"
echo '{"length_m": 2.5}' > "$W/t_no_d.json"
"$expect" 3 "$o" 'diameter_m' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" \
  --camera "$T/theo/camera.json" --target "$W/t_no_d.json" -o "$o"
"$expect" 4 "$o" 'nope.csv' -- rk-attitude cylinder --points "$W/nope.csv" "${args[@]}"
"$expect" 2 "$o" -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" \
  --camera "$T/theo/camera.json" -o "$o"
"$expect" 2 - -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" \
  --camera "$T/theo/camera.json" --target "$T/target.json" -o "$T/points.csv"
"$expect" 2 "$o" 'stdin' -- rk-attitude cylinder --points - --theodolite - --camera "$T/theo/camera.json" \
  --target "$T/target.json" -o "$o"
"$expect" 2 "$o" -- rk-attitude cylinder --points "$T/points.csv" "${args[@]}" --ambiguity-deg 0
"$expect" 2 - -- rk-attitude
echo ok
