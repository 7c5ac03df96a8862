# CLI tests of rk-sim theodolite (SPEC.md §4, docs/rk-sim.md). The fixture sim_theodolite_trial writes
# ${RK_CLI_DATA}/theo_trial (640x640 sensor of seed 004's optics, 5 frames with PNG images) for the
# rk-attitude cylinder and rk-extract silhouette CLI tests to REQUIRE.
# Shell scripts get $1 = RK_CLI_DATA, $2 = expect.sh; the rk-* tools are on PATH.
function(rk_sim_theo_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_sim_theo_script(rk_sim_theodolite_trial [==[
d=$data/theo_trial
out=$(rk-sim theodolite --out "$d" --force --sensor-px 640 --duration 0.2 --speed-mps 50 --images png \
      --track-error-px 10 --report "$data/theo_trial.json")
test -z "$out"
for f in trial.json target.json theodolite.csv points.csv theo/camera.json theo/frames.csv theo/000000.png \
         theo/000004.png truth/axis.csv truth/points.csv truth/theodolite.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/points.csv")" = "frame,t_s,id,x_px,y_px"
test "$(head -n 1 "$d/theodolite.csv")" = "t_s,az_deg,el_deg"
head -n 1 "$d/truth/axis.csv" | grep -q '^frame,t_s,yaw_deg,pitch_deg,alt_yaw_deg,alt_pitch_deg,range_nose_m'
test "$(grep -c '' "$d/points.csv")" = 16          # header + 5 frames x 3 points
test ! -e "$d/theo/000005.png"
# Truth: the seed 004 attitude, ids in order, the manifest names the silhouette camera and the theodolite.
grep -q '^0,1.000000000,76.211000000,31.257000000,' "$d/truth/axis.csv"
test "$(cut -d, -f3 "$d/points.csv" | sed -n '2,4p' | tr '\n' ' ')" = "nose tail1 tail2 "
grep -q '"role": "silhouette"' "$d/trial.json"
grep -q '"theodolite": "theodolite.csv"' "$d/trial.json"
grep -q '"length_m": 2.5' "$d/target.json"
grep -q '"frames": 5' "$data/theo_trial.json"
echo ok
]==] SETUP sim_theodolite_trial)

# Quantised points are whole pixels; --angle-budget seed004 biases the log; same seed → same files.
rk_sim_theo_script(rk_sim_theodolite_quantise_budget [==[
d=$data/theo_q; rm -rf "$d"; mkdir -p "$d"
rk-sim theodolite --out "$d/a" --quantise --angle-budget seed004 --seed 4 --duration 0.5 --quiet
rk-sim theodolite --out "$d/b" --quantise --angle-budget seed004 --seed 4 --duration 0.5 --quiet
diff -r -x trial.json "$d/a" "$d/b"
diff <(grep -v '"name"' "$d/a/trial.json") <(grep -v '"name"' "$d/b/trial.json")
awk -F, 'NR > 1 && ($4 != int($4) || $5 != int($5)) { bad = 1 } END { exit bad }' "$d/a/points.csv"
# The recorded angles differ from the true ones by the seed 004 budget (5.1' bias RSS): not zero, < 30'.
paste -d, "$d/a/theodolite.csv" "$d/a/truth/theodolite.csv" | awk -F, 'NR > 1 { e = ($3 - $6) * 60; if (e < 0) e = -e;
  if (e > m) m = e } END { exit !(m > 0.01 && m < 30) }'
echo ok
]==])

# Bad usage → 2, nothing written; unwritable → 4.
rk_cli_test(rk_sim_theodolite_bad_range COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad1 "range" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad1 --range-m 5)
rk_cli_test(rk_sim_theodolite_bad_images COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad2 "images" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad2 --images gif)
rk_cli_test(rk_sim_theodolite_budget_and_bias COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad3 "angle-budget" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad3 --angle-budget seed004 --angle-bias-arcsec 3)
rk_cli_test(rk_sim_theodolite_leaves_image COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad4 "leaves the" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad4 --sensor-px 128)
rk_sim_theo_script(rk_sim_theodolite_refuses_nonempty_out [==[
d=$data/theo_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim theodolite --out "$d"
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.theo_keep'; then echo "temporary folder left"; exit 1; fi
echo ok
]==])
rk_sim_theo_script(rk_sim_theodolite_unwritable_out [==[
f=$data/theo_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim theodolite --out "$f/run"
echo ok
]==])
