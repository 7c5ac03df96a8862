# CLI tests of rk-extract features (SPEC.md §1.1, §4) on the sim_attitude_small trial
# (rk_sim_attitude.cmake): good input scored against the truth, and malformed input. The good
# run is the fixture features_small used by rk-attitude oi's tests.
# rk_extract_features_script(name body [REQUIRES fixture...] [SETUP fixture])
function(rk_extract_features_script name body)
  cmake_parse_arguments(ARG "" "SETUP" "REQUIRES" ${ARGN})
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
       "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; src=$3\nd=$data/att_small\n${body}")
  rk_cli_test(${name} REQUIRES ${ARG_REQUIRES} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT} ${RK_SOURCE_DIR})
  if(ARG_SETUP)
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP ${ARG_SETUP})
  endif()
endfunction()

# Every marker found with its own id (no identity error), sub-0.05 px, the hidden fin lost for
# 3 frames then reacquired; report counts.
rk_extract_features_script(rk_extract_features_good [==[
rm -f "$data/att_points.csv" "$data/att_points.json"
out=$(rk-extract features --video "$d/att/video.mkv" --frames "$d/att/frames.csv" --target "$d/target.json" \
      -o "$data/att_points.csv" --report "$data/att_points.json")
test -z "$out"
test "$(head -n 1 "$data/att_points.csv")" = "frame,t_s,id,x_px,y_px,status,sigma_px,ncc,radius_px"
test "$(grep -c '' "$data/att_points.csv")" = 81
test "$(grep -c ',fin,,,lost,' "$data/att_points.csv")" = 3
test "$(grep -c ',fin,[0-9.]*,[0-9.]*,reacquired,' "$data/att_points.csv")" = 1
python3 "$src/bench/attitude_points_stats.py" "$data/att_points.csv" "$d/truth/points.csv" | tee "$data/att_points_stats.txt"
grep -q 'identity errors 0 ' "$data/att_points_stats.txt"
awk '/rms/ { if ($7 > 0.05 || $14 > 0.05) exit 1 }' "$data/att_points_stats.txt"
grep -q '"ok": 1' "$data/att_points.json"
grep -q '"frames_with_4_points": 10' "$data/att_points.json"
echo ok
]==] REQUIRES sim_attitude_small SETUP features_small)

# --fps/--t0 and stdout; the same points as with frames.csv (t0 = 1 s, 10 fps).
rk_extract_features_script(rk_extract_features_fps_stdout [==[
rk-extract features --video "$d/att/video.mkv" --fps 10 --t0 1 --target "$d/target.json" -o - > "$data/att_points_fps.csv"
cmp "$data/att_points_fps.csv" "$data/att_points.csv"
echo ok
]==] REQUIRES sim_attitude_small features_small)

# Nothing to find: every marker hidden → exit 1 (SPEC: nothing detected at all), no output.
rk_extract_features_script(rk_extract_features_nothing [==[
e=$data/att_empty
hides=""
for id in belly canopy fin ltail lwing nose rwing tail; do hides="$hides --hide $id:0:5"; done
rk-sim attitude --out "$e" --force --camera "$data/att_cam.json" --range-m 40 --duration 0.3 --fps 10 --quiet $hides
"$expect" 1 "$data/att_none.csv" 'nothing detected' -- rk-extract features --video "$e/att/video.mkv" --fps 10 --target "$d/target.json" -o "$data/att_none.csv"
echo ok
]==] REQUIRES sim_attitude_small)

# Malformed input and usage.
rk_extract_features_script(rk_extract_features_bad [==[
o=$data/att_bad_points.csv; rm -f "$o"
"$expect" 2 "$o" 'frames' -- rk-extract features --video "$d/att/video.mkv" --target "$d/target.json" -o "$o"
"$expect" 2 "$o" 'target' -- rk-extract features --video "$d/att/video.mkv" --fps 10 -o "$o"
"$expect" 2 - 'input' -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$d/target.json"
printf '{"length_m": 1.2, "diameter_m": 0.2}' > "$data/att_cyl.json"
"$expect" 3 "$o" "att_cyl.json.*points" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$data/att_cyl.json" -o "$o"
printf '{"points": {"a": [0,0,0], "b": [1,0' > "$data/att_trunc.json"
"$expect" 3 "$o" "att_trunc.json:1:" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$data/att_trunc.json" -o "$o"
head -n 6 "$d/att/frames.csv" > "$data/att_frames_short.csv"
"$expect" 3 "$o" "att_frames_short.csv" -- rk-extract features --video "$d/att/video.mkv" --frames "$data/att_frames_short.csv" --target "$d/target.json" -o "$o"
"$expect" 4 "$o" -- rk-extract features --video "$data/no_such_video.mkv" --fps 10 --target "$d/target.json" -o "$o"
"$expect" 2 "$o" 'polarity' -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$o" --polarity grey
"$expect" 2 "$o" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$o" --gate 0.9
test ! -e "$d/target.json.tmp"
echo ok
]==] REQUIRES sim_attitude_small)

# Image-sequence input (rk-sim --format png) given as two segments: frame numbers count on, the
# second copy is read as frames 5-9 (10 frames x 8 ids = 80 rows).
rk_extract_features_script(rk_extract_features_png_segments [==[
p=$data/att_png
rk-sim attitude --out "$p" --force --format png --camera "$data/att_cam.json" --range-m 40 --duration 0.5 --fps 10 --quiet
test -s "$p/att/000004.png"
rk-extract features --video "$p/att/%06d.png" --video "$p/att/%06d.png" --fps 10 --t0 1 --target "$p/target.json" \
  -o "$data/att_png_points.csv" --quiet
test "$(grep -c '' "$data/att_png_points.csv")" = 81
test "$(tail -n 1 "$data/att_png_points.csv" | cut -d, -f1-3)" = "9,1.900000000,tail"
test "$(awk -F, 'NR > 1 && $6 != "ok"' "$data/att_png_points.csv" | grep -c '')" = 0
echo ok
]==] REQUIRES sim_attitude_small)

# 16-bit video: the same thresholds in noise sigmas work on 16-bit DN.
rk_extract_features_script(rk_extract_features_16bit [==[
p=$data/att_16
rk-sim attitude --out "$p" --force --bit-depth 16 --camera "$data/att_cam.json" --range-m 40 --duration 0.5 --fps 10 --quiet
rk-extract features --video "$p/att/video.mkv" --frames "$p/att/frames.csv" --target "$p/target.json" -o "$data/att_16_points.csv" --quiet
python3 "$src/bench/attitude_points_stats.py" "$data/att_16_points.csv" "$p/truth/points.csv" | tee "$data/att_16_stats.txt"
grep -q "identity errors 0  status {'ok': 40}" "$data/att_16_stats.txt"
awk '/rms/ { if ($7 > 0.05 || $14 > 0.05) exit 1 }' "$data/att_16_stats.txt"
echo ok
]==] REQUIRES sim_attitude_small)
