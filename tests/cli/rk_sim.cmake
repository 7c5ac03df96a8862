# CLI tests of rk-sim (SPEC.md §4). The fixture sim_small writes the trial
# ${RK_CLI_DATA}/small that other tools' CLI tests REQUIRE:
#   small preset (640x512), 3 s at 20 fps (60 frames), FFV1 mkv, seed 1, one
#   0.5 s occlusion from 1.5 s after frame 0 (frames 30-39), one distractor; the
#   range error rate is raised to 0.05 so that the 3 s range log contains a
#   device-error row (status 255, empty range_m).
# Shell scripts are written to the build folder and get: $1 = RK_CLI_DATA,
# $2 = expect.sh; rk-sim is found on PATH (rk_cli_test puts RK_BIN first).
set(RK_SIM $<TARGET_FILE:rk-sim>)

function(rk_sim_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_sim_script(rk_sim_small [==[
d=$data/small
out=$(rk-sim beacon --out "$d" --force --preset small --duration 3 --format mkv --seed 1 \
      --occlusion 1.5:0.5 --distractors 1 --range-error-rate 0.05 --quiet)
test -z "$out"
for f in trial.json az/camera.json az/frames.csv az/video.mkv turret.csv range.csv \
         truth/beacon.csv truth/target.csv truth/turret.csv truth/range.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(grep -c '' "$d/az/frames.csv")" = 61
test "$(grep -c ',,0,' "$d/truth/beacon.csv")" = 10
grep -q ',,255$' "$d/range.csv"
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=width,height,nb_read_frames \
    -of csv=p=0 "$d/az/video.mkv")
test "$n" = "640,512,60" || { echo "video: $n"; exit 1; }
echo "sim_small ok"
]==] SETUP sim_small)

# Same seed → identical trial (apart from the manifest's name); PNG, 16-bit, report.
rk_sim_script(rk_sim_deterministic_png16 [==[
d=$data/sim_det; rm -rf "$d"; mkdir -p "$d"
for x in a b; do
  rk-sim beacon --out "$d/$x" --preset small --duration 0.5 --format png --bit-depth 16 --seed 7 \
    --distractors 2 --report "$d/$x.json"
done
test -s "$d/a/az/000009.png"
test ! -e "$d/a/az/000010.png"
diff -r -x trial.json "$d/a" "$d/b"
grep -q '"visible_frames": 10' "$d/a.json"
rk-sim beacon --out "$d/c" --preset small --duration 0.5 --format png --bit-depth 16 --seed 8 --distractors 2
if cmp -s "$d/a/az/000000.png" "$d/c/az/000000.png"; then echo "seed has no effect"; exit 1; fi
echo ok
]==])

# Bad usage → 2, nothing written.
rk_cli_test(rk_sim_unknown_option COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad1 --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad1 --preset small --bogus 1)
rk_cli_test(rk_sim_no_subcommand COMMAND ${RK_EXPECT} 2 - -- ${RK_SIM} --out ${RK_CLI_DATA}/sim_bad2)
rk_cli_test(rk_sim_missing_out COMMAND ${RK_EXPECT} 2 - "--out" -- ${RK_SIM} beacon --preset small)
rk_cli_test(rk_sim_bad_lamps COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad3 "lamps" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad3 --preset small --duration 0.5 --lamps 3)
rk_cli_test(rk_sim_bad_occlusion COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad4 "occlusion" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad4 --preset small --duration 0.5 --occlusion 1.5)
rk_cli_test(rk_sim_bad_range COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad5 "range" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad5 --preset small --duration 0.5 --range-m 5)
rk_cli_test(rk_sim_bad_format COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad6 --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad6 --preset small --duration 0.5 --format avi)
rk_cli_test(rk_sim_target_leaves_image COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad7 "leaves the image" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad7 --preset small --duration 2 --trajectory straight
  --range-m 20 --speed-mps 100)

# Existing non-empty --out without --force → 2, and the folder is left exactly as it was.
rk_sim_script(rk_sim_refuses_nonempty_out [==[
d=$data/sim_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim beacon --out "$d" --preset small --duration 0.5
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
test "$(cat "$d/keep.txt")" = precious || { echo "file changed"; exit 1; }
if ls -A "$data" | grep -q '^\.sim_keep'; then echo "temporary folder left"; exit 1; fi
# With --force it is replaced as a whole.
rk-sim beacon --out "$d" --force --preset small --duration 0.5 --format png
test ! -e "$d/keep.txt"
test -s "$d/trial.json"
if ls -A "$data" | grep -q '^\.sim_keep'; then echo "old folder left"; exit 1; fi
echo ok
]==])

# Unwritable --out → 4, nothing written.
rk_sim_script(rk_sim_unwritable_out [==[
f=$data/sim_file; echo x > "$f"
"$expect" 4 "$f/trial" -- rk-sim beacon --out "$f/trial" --preset small --duration 0.5
"$expect" 4 - -- rk-sim beacon --out /proc/rk_sim_nowhere/trial --preset small --duration 0.5
echo ok
]==])
# --servo-hold (issue 15 item 2): malformed → 2 naming the option; a good one is recorded in the report.
rk_cli_test(rk_sim_bad_servo_hold COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad_hold "servo-hold" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad_hold --preset small --duration 0.5 --servo-hold 0.2)
rk_sim_script(rk_sim_servo_hold_report [==[
d=$data/sim_hold; rm -rf "$d" "$d.json"
rk-sim beacon --out "$d" --preset small --duration 1 --servo-hold 0.3:0.2 --report "$d.json" --quiet
python3 -c "import json,sys; h=json.load(open(sys.argv[1]))['options']['servo_holds']; sys.exit(h != [{'start_s': 0.3, 'duration_s': 0.2}])" "$d.json"
echo ok
]==])
