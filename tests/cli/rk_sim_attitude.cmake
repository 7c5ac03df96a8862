# CLI tests of rk-sim attitude (SPEC.md §4, docs/rk-sim.md). The fixture sim_attitude_small
# writes ${RK_CLI_DATA}/att_small: a 1000x800 sensor with the 100 mm lens (3.45 um pixels), the
# default 8-marker target at 40 m (markers ~8 px radius), 1 s at 10 fps (10 frames), the fin
# hidden for 0.3 s; rk-extract features and rk-attitude oi tests REQUIRE it.
# Shell scripts get $1 = RK_CLI_DATA, $2 = expect.sh; rk-sim is on PATH.
function(rk_sim_attitude_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_sim_attitude_script(rk_sim_attitude_small [==[
cat > "$data/att_cam.json" <<'EOF'
{"width_px": 1000, "height_px": 800, "pixel_size_mm": [0.00345, 0.00345], "focal_length_mm": 100.0,
 "principal_point_px": [499.5, 399.5], "distortion": [-0.02, 0, 0, 0, 0], "mount_deg": {"yaw": 0.02, "pitch": -0.01, "roll": 0.1}}
EOF
d=$data/att_small
out=$(rk-sim attitude --out "$d" --force --camera "$data/att_cam.json" --range-m 40 --duration 1 --fps 10 \
      --seed 1 --hide fin:0.3:0.3 --report "$data/att_small.json")
test -z "$out"
for f in trial.json target.json turret.csv att/camera.json att/frames.csv att/video.mkv truth/pose.csv truth/points.csv truth/turret.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/truth/pose.csv")" = "frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,range_m,boresight_az_deg,boresight_el_deg"
test "$(head -n 1 "$d/truth/points.csv")" = "frame,t_s,id,x_px,y_px,status,radius_px"
test "$(grep -c '' "$d/truth/pose.csv")" = 11
test "$(grep -c '' "$d/truth/points.csv")" = 81
test "$(grep -c ',fin,,,lost,' "$d/truth/points.csv")" = 3     # t = 1.3, 1.4, 1.5 s
grep -q '"role": "features"' "$d/trial.json"
grep -q '"target": "target.json"' "$d/trial.json"
grep -q '"nose": \[' "$d/target.json"
grep -q '"frames": 10' "$data/att_small.json"
# Initial attitude: yaw 300, pitch 5, roll 0 (the defaults) at frame 0.
grep -q '^0,1.000000000,[^,]*,[^,]*,[^,]*,300.000000000,5.000000000,0.000000000,' "$d/truth/pose.csv"
echo ok
]==] SETUP sim_attitude_small)

# Same seed → same truth; yaw across 0/360 and roll across ±180 written in their SPEC ranges.
rk_sim_attitude_script(rk_sim_attitude_wraps_and_determinism [==[
d=$data/att_wrap; rm -rf "$d"; mkdir -p "$d"
rk-sim attitude --out "$d/a" --name w --no-video --fps 2 --yaw0-deg 355 --roll0-deg 177 --path-angle-deg 0 --quiet
rk-sim attitude --out "$d/b" --name w --no-video --fps 2 --yaw0-deg 355 --roll0-deg 177 --path-angle-deg 0 --quiet
diff -r "$d/a" "$d/b" >/dev/null || { echo "not deterministic"; exit 1; }
awk -F, 'NR > 1 { if ($6 < 0 || $6 >= 360 || $8 <= -180 || $8 > 180) bad = 1;
                  if ($6 < 5) ylo = 1; if ($6 > 355) yhi = 1; if ($8 > 177) rp = 1; if ($8 < -178) rn = 1 }
         END { exit !(ylo && yhi && rp && rn && !bad) }' "$d/a/truth/pose.csv"
test ! -e "$d/a/att/video.mkv"
# No video, no camera in the manifest (SPEC.md §6 wants a non-empty video list): rk-run has nothing to extract
python3 -c "import json,sys; m = json.load(open(sys.argv[1])); assert m['cameras'] == {}, m['cameras']" "$d/a/trial.json"
echo ok
]==])

# Bad usage → 2, nothing written; bad target file → 3; unwritable → 4.
rk_cli_test(rk_sim_attitude_bad_bitdepth COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad1 "bit-depth" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad1 --bit-depth 12)
rk_cli_test(rk_sim_attitude_bad_hide COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad2 "nosecone" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad2 --hide nosecone:0:1)
rk_cli_test(rk_sim_attitude_hide_syntax COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad3 "ID:START_S:DURATION_S" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad3 --hide fin:1)
rk_cli_test(rk_sim_attitude_too_close COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad4 "leaves the 2448x2048 image" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad4 --range-m 5 --approach-m 1 --return-m 1 --no-video)
rk_sim_attitude_script(rk_sim_attitude_bad_target [==[
printf '{"points": {"a": [0,0,0], "b": [1,0,0], "c": [2,0,0], "d": [3,0,0]}}' > "$data/att_line.json"
"$expect" 3 "$data/att_bad5" 'att_line.json.*collinear' -- rk-sim attitude --out "$data/att_bad5" --target "$data/att_line.json" --no-video
echo ok
]==])
rk_sim_attitude_script(rk_sim_attitude_refuses_nonempty_out [==[
d=$data/att_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim attitude --out "$d" --no-video --duration 1
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.att_keep'; then echo "temporary folder left"; exit 1; fi
rk-sim attitude --out "$d" --force --no-video --duration 1 --quiet
test ! -e "$d/keep.txt"
test -s "$d/truth/pose.csv"
f=$data/att_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim attitude --out "$f/run" --no-video --duration 1
echo ok
]==])
