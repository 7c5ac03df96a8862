# CLI tests of rk-attitude cylinder (SPEC.md §1.1, §4; docs/rk-attitude-cylinder.md) on the trial of the
# fixture sim_theodolite_trial (tests/cli/rk_sim_theodolite.cmake): good input and malformed input.
function(rk_att_cyl_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\nT=$data/theo_trial\nW=$data/att_cyl; mkdir -p \"$W\"\n${body}")
  rk_cli_test(${name} ${ARGN} REQUIRES sim_theodolite_trial
              COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

# Exact points: the truth to 1e-4 deg, the mirror in alt_*, one row per frame, report, both methods.
rk_att_cyl_script(rk_attitude_cylinder_good [==[
rm -f "$W/axis.csv" "$W/rep.json"
out=$(rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
      --target "$T/target.json" -o "$W/axis.csv" --report "$W/rep.json" --quiet)
test -z "$out"
head -n 1 "$W/axis.csv" | grep -q '^frame,t_s,yaw_deg,pitch_deg,status,alt_yaw_deg,alt_pitch_deg,solution,range_nose_m,range_tail1_m,range_tail2_m,sigma_yaw_deg,sigma_pitch_deg'
test "$(grep -c '' "$W/axis.csv")" = 6
test "$(cut -d, -f5 "$W/axis.csv" | sort -u | tr '\n' ' ')" = "ok status "
rk-analyze compare --estimate "$W/axis.csv" --reference "$T/truth/axis.csv" --columns yaw_deg,pitch_deg,alt_yaw_deg,range_nose_m \
  -o "$W/stats.json"
python3 - "$W/stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k, tol in (("yaw_deg", 1e-4), ("pitch_deg", 1e-4), ("alt_yaw_deg", 1e-4), ("range_nose_m", 1e-2)):
    assert c[k]["n"] == 5 and abs(c[k]["max"]) < tol and abs(c[k]["min"]) < tol, (k, c[k])
PY
grep -q '"ambiguous": 1' "$W/rep.json"
grep -q '"continuity": 4' "$W/rep.json"
rk-attitude cylinder --method search --points "$T/points.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" -o "$W/axis_search.csv" --quiet
diff <(cut -d, -f1-4 "$W/axis.csv") <(cut -d, -f1-4 "$W/axis_search.csv")
echo ok
]==])

# -o - writes to stdout; the points may come from stdin.
rk_att_cyl_script(rk_attitude_cylinder_stdio [==[
rk-attitude cylinder --points - --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" --target "$T/target.json" \
  -o - --quiet < "$T/points.csv" | awk -F, 'NR > 1 && $5 == "ok" { n++ } END { exit n != 5 }'
echo ok
]==])

# Bad input: one-line error, SPEC.md §4 exit code, no output file.
rk_att_cyl_script(rk_attitude_cylinder_bad_input [==[
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
]==])

# Per-row statuses: a missing point is lost, frames in a theodolite gap are invalid, the others keep their values.
rk_att_cyl_script(rk_attitude_cylinder_row_status [==[
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
]==])

# Image fit (--video): rk-extract silhouette points refined on the fixture's own frames. Tolerances 4σ of one
# frame at this 298-px image (the fit's σ ≈ 0.055° yaw, 0.021° pitch); bad input: no frame column, a video
# shorter than the points file.
rk_att_cyl_script(rk_attitude_cylinder_image_fit [==[
rm -f "$W/fit.csv" "$W/sil.csv"
rk-extract silhouette --video "$T/theo/%06d.png" --frames "$T/theo/frames.csv" -o "$W/sil.csv" --quiet
rk-attitude cylinder --points "$W/sil.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" --video "$T/theo/%06d.png" -o "$W/fit.csv" --report "$W/fit.json" --quiet
head -n 1 "$W/fit.csv" | grep -q ',fit,fit_rms_dn,fit_psf_px,fit_cone_m,fit_iterations$'
awk -F, 'NR > 1 && $19 == "converged" { n++ } END { exit n != 5 }' "$W/fit.csv"
grep -q '"converged": 5' "$W/fit.json"
rk-analyze compare --estimate "$W/fit.csv" --reference "$T/truth/axis.csv" --columns yaw_deg,pitch_deg -o "$W/fit_stats.json"
python3 - "$W/fit_stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k, tol in (("yaw_deg", 0.25), ("pitch_deg", 0.10)):
    assert c[k]["n"] == 5 and c[k]["max"] < tol and c[k]["min"] > -tol, (k, c[k])
PY
o=$W/fit_bad.csv; rm -f "$o"
args=(--theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" --target "$T/target.json" -o "$o")
cut -d, -f2- "$W/sil.csv" > "$W/sil_noframe.csv"
"$expect" 2 "$o" 'frame. column' -- rk-attitude cylinder --points "$W/sil_noframe.csv" "${args[@]}" --video "$T/theo/%06d.png"
mkdir -p "$W/short"; cp "$T/theo/000000.png" "$T/theo/000001.png" "$W/short/"
"$expect" 3 "$o" 'ends after 2 frames' -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$W/short/%06d.png"
"$expect" 4 "$o" -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$W/none/%06d.png"
"$expect" 2 "$o" -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$T/theo/%06d.png" --fit-psf-sigma 0
echo ok
]==])
