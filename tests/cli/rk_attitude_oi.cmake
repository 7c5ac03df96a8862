# CLI tests of rk-attitude oi (SPEC.md §1.1, §4) on the sim_attitude_small trial and the points
# extracted from its video (fixture features_small): accuracy against the truth, per-row status
# for turret gaps and missing points, and malformed input.
# rk_attitude_oi_script(name body [REQUIRES fixture...])
function(rk_attitude_oi_script name body)
  cmake_parse_arguments(ARG "" "" "REQUIRES" ${ARGN})
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
       "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\nd=$data/att_small\n${body}")
  rk_cli_test(${name} REQUIRES ${ARG_REQUIRES} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

# Extracted points → pose; errors against the truth: yaw/pitch/roll std well under 0.05 deg.
rk_attitude_oi_script(rk_attitude_oi_good [==[
o=$data/att_pose.csv; rm -f "$o"
out=$(rk-attitude oi --points "$data/att_points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
      --turret "$d/turret.csv" -o "$o" --report "$data/att_pose.json")
test -z "$out"
head -n 1 "$o" | grep -q '^frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status,reproj_rms_px,'
test "$(grep -c '' "$o")" = 11
test "$(cut -d, -f9 "$o" | sort | uniq -c | awk '{print $1 $2}' | tr '\n' ' ')" = "10ok 1status "
rk-analyze compare --estimate "$o" --reference "$d/truth/pose.csv" --columns yaw_deg,pitch_deg,roll_deg,e_m,n_m,u_m \
  -o "$data/att_pose_stats.json"
python3 - "$data/att_pose_stats.json" <<'EOF'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k in ("yaw_deg", "pitch_deg", "roll_deg"):
    assert abs(c[k]["max"]) < 0.05 and abs(c[k]["min"]) < 0.05, (k, c[k])
for k in ("e_m", "n_m", "u_m"):
    assert abs(c[k]["max"]) < 0.02 and abs(c[k]["min"]) < 0.02, (k, c[k])
print("ok", {k: c[k]["std"] for k in c})
EOF
grep -q '"ok": 10' "$data/att_pose.json"
grep -q '"mean_chi2_per_dof"' "$data/att_pose.json"
# Frames with the fin hidden used 7 points.
test "$(awk -F, 'NR > 1 && $12 == 7' "$o" | grep -c '')" = 3
echo ok
]==] REQUIRES sim_attitude_small features_small)

# Truth points (no image noise) with a fixed boresight, to stdout; --pure-oi also runs.
rk_attitude_oi_script(rk_attitude_oi_boresight_stdout [==[
rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --boresight 30,3 -o - | awk -F, 'NR > 1 && $9 == "ok" { n++ } END { exit n != 10 }'
rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$d/turret.csv" --pure-oi -o - | awk -F, 'NR > 1 && $9 == "ok" { n++ } END { exit n != 10 }'
echo ok
]==] REQUIRES sim_attitude_small)

# Per-row status: a turret-log hole → invalid (note turret); a frame with 3 points → lost.
rk_attitude_oi_script(rk_attitude_oi_row_status [==[
awk -F, 'NR == 1 || $1 < 1.25 || $1 > 1.45' "$d/turret.csv" > "$data/att_turret_gap.csv"
awk -F, 'NR == 1 || $1 != 7 || $3 == "nose" || $3 == "tail" || $3 == "lwing"' "$d/truth/points.csv" > "$data/att_pts3.csv"
rk-attitude oi --points "$data/att_pts3.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$data/att_turret_gap.csv" -o "$data/att_pose_gap.csv" --quiet
grep -q '^3,1.300000000,,,,,,,invalid,.*,turret,,$' "$data/att_pose_gap.csv"
grep -q '^7,1.700000000,,,,,,,lost,,,3,.*,few_points,' "$data/att_pose_gap.csv"
grep -q '^8,1.800000000,.*,reacquired,' "$data/att_pose_gap.csv"
# The warning names the turret log.
rk-attitude oi --points "$data/att_pts3.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$data/att_turret_gap.csv" -o "$data/att_pose_gap_warn.csv" 2>&1 | grep -q 'warning: 2 of 10 frame times are not covered by'
echo ok
]==] REQUIRES sim_attitude_small)

# Malformed input and usage (SPEC.md §4): one-line error, exit code, no output.
rk_attitude_oi_script(rk_attitude_oi_bad [==[
o=$data/att_bad_pose.csv; rm -f "$o"
P="--camera $d/att/camera.json --target $d/target.json"
sed 's/,nose,/,nose2,/' "$d/truth/points.csv" > "$data/att_badid.csv"
"$expect" 3 "$o" "att_badid.csv:[0-9]+:[0-9]+: .*id 'nose2' is not in the target model" -- rk-attitude oi --points "$data/att_badid.csv" $P --turret "$d/turret.csv" -o "$o"
awk -F, 'NR == 1 || $3 == "nose" || $3 == "tail" || $3 == "lwing"' "$d/truth/points.csv" > "$data/att_three.csv"
"$expect" 1 "$o" 'no pose in any of the 10 frames' -- rk-attitude oi --points "$data/att_three.csv" $P --turret "$d/turret.csv" -o "$o"
sed '2s/,belly,[0-9.]*,/,belly,5000.5,/' "$d/truth/points.csv" > "$data/att_outside.csv"
"$expect" 3 "$o" 'att_outside.csv:2:[0-9]+: .*outside the 1000x800 image' -- rk-attitude oi --points "$data/att_outside.csv" $P --turret "$d/turret.csv" -o "$o"
sed '3s/,canopy,/,belly,/' "$d/truth/points.csv" > "$data/att_dup.csv"
"$expect" 3 "$o" 'att_dup.csv:3:[0-9]+: .*twice' -- rk-attitude oi --points "$data/att_dup.csv" $P --turret "$d/turret.csv" -o "$o"
printf '{"points": {"a": [0,0,0], "b": [0.1,0,0], "c": [0.2,0,0], "d": [0.3,0,0]}}' > "$data/att_line2.json"
"$expect" 3 "$o" 'collinear' -- rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$data/att_line2.json" --turret "$d/turret.csv" -o "$o"
"$expect" 2 "$o" 'turret' -- rk-attitude oi --points "$d/truth/points.csv" $P -o "$o"
"$expect" 2 "$o" -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" --boresight 30,3 -o "$o"
"$expect" 2 "$o" 'elevation' -- rk-attitude oi --points "$d/truth/points.csv" $P --boresight 30,95 -o "$o"
"$expect" 2 "$o" 'AZ,EL' -- rk-attitude oi --points "$d/truth/points.csv" $P --boresight 30 -o "$o"
"$expect" 2 "$o" 'min-points' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" --min-points 3 -o "$o"
printf 't_s,az_deg,el_deg\n500,30,3\n500.02,30,3\n' > "$data/att_turret_late.csv"
"$expect" 3 "$o" 'att_turret_late.csv.*no frame time' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$data/att_turret_late.csv" -o "$o"
"$expect" 2 - 'input' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" -o "$d/turret.csv"
"$expect" 4 "$o" -- rk-attitude oi --points "$data/no_such_points.csv" $P --turret "$d/turret.csv" -o "$o"
printf 'frame,t_s,id,x_px,y_px\n0,1.0,nose,500,400\n1,0.9,nose,500,400\n' > "$data/att_back.csv"
"$expect" 3 "$o" 'att_back.csv:3:' -- rk-attitude oi --points "$data/att_back.csv" $P --turret "$d/turret.csv" -o "$o"
echo ok
]==] REQUIRES sim_attitude_small)
