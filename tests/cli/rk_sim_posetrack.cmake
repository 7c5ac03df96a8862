# CLI tests of rk-sim posetrack (SPEC.md §4, docs/rk-sim.md). The fixture
# sim_posetrack_turntable writes ${RK_CLI_DATA}/posetrack_turntable (seed 000's turntable
# experiment, seed 1: 181 samples 0-9 s, 180 mid-times) for rk-smooth's CLI tests to REQUIRE.
# Shell scripts get $1 = RK_CLI_DATA, $2 = expect.sh; rk-sim is on PATH.
function(rk_sim_posetrack_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_sim_posetrack_script(rk_sim_posetrack_turntable [==[
d=$data/posetrack_turntable
out=$(rk-sim posetrack --out "$d" --force --scenario turntable --seed 1 --report "$data/posetrack_turntable.json")
test -z "$out"
for f in measurements.csv truth.csv truth_sample.csv truth_mid.csv scenario.json; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/measurements.csv")" = "t_s,x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg"
head -n 1 "$d/truth.csv" | grep -q '^t_s,kind,x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg,.*yaw_rate_deg_s'
test "$(grep -c '' "$d/measurements.csv")" = 182      # header + 181 samples
test "$(grep -c ',sample,' "$d/truth.csv")" = 181
test "$(grep -c ',mid,' "$d/truth.csv")" = 180
# Truth: yaw 20 deg at t = 0, 20.25 deg at the first mid-time, 110 deg at 9 s; 10 deg/s throughout.
grep -q '^0.000000000,sample,0.050000000,-0.020000000,0.800000000,20.000000000,10.000000000,-5.000000000,' "$d/truth.csv"
grep -q '^0.025000000,mid,[^,]*,[^,]*,[^,]*,20.250000000,' "$d/truth.csv"
grep -q '^9.000000000,sample,[^,]*,[^,]*,[^,]*,110.000000000,' "$d/truth.csv"
test "$(cut -d, -f12 "$d/truth.csv" | sort -u)" = "$(printf '10.000000000\nyaw_rate_deg_s')"
grep -q '"scenario": "turntable"' "$d/scenario.json"
grep -q '"samples": 181' "$data/posetrack_turntable.json"
echo ok
]==] SETUP sim_posetrack_turntable)

# Head scenario: yaw written in [0, 360) and crossing north; same seed → same files; dropout rows empty.
rk_sim_posetrack_script(rk_sim_posetrack_head [==[
d=$data/posetrack_head; rm -rf "$d"; mkdir -p "$d"
rk-sim posetrack --out "$d/a" --scenario head --duration 10 --seed 3 --dropout 0.1 --quiet
rk-sim posetrack --out "$d/b" --scenario head --duration 10 --seed 3 --dropout 0.1 --quiet
rk-sim posetrack --out "$d/c" --scenario head --duration 10 --seed 4 --dropout 0.1 --quiet
diff -r "$d/a" "$d/b"
if cmp -s "$d/a/measurements.csv" "$d/c/measurements.csv"; then echo "seed has no effect"; exit 1; fi
test "$(grep -c '' "$d/a/measurements.csv")" = 202
grep -q '^[0-9.]*,,,,,,$' "$d/a/measurements.csv"     # a dropped row keeps its time
# yaw column (6): all in [0, 360), both near 0 and near 360 (crosses north).
awk -F, 'NR > 1 { if ($6 < 0 || $6 >= 360) bad = 1; if ($6 < 90) lo = 1; if ($6 > 270) hi = 1 }
         END { exit !(lo && hi && !bad) }' "$d/a/truth.csv"
echo ok
]==])

# Bad usage → 2, nothing written.
rk_cli_test(rk_sim_posetrack_unknown_scenario COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad1 "scenario" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad1 --scenario spin)
rk_cli_test(rk_sim_posetrack_bad_noise COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad2 "noise" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad2 --noise-deg -1)
rk_cli_test(rk_sim_posetrack_rate_with_head COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad3 "turntable only" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad3 --scenario head --rate-deg-s 5)
rk_cli_test(rk_sim_posetrack_bad_dropout COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad4 "dropout" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad4 --dropout 1)
rk_sim_posetrack_script(rk_sim_posetrack_refuses_nonempty_out [==[
d=$data/pt_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim posetrack --out "$d" --scenario head
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.pt_keep'; then echo "temporary folder left"; exit 1; fi
rk-sim posetrack --out "$d" --force --duration 1
test ! -e "$d/keep.txt"
test "$(grep -c '' "$d/measurements.csv")" = 22
echo ok
]==])
rk_sim_posetrack_script(rk_sim_posetrack_unwritable_out [==[
f=$data/pt_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim posetrack --out "$f/run"
echo ok
]==])
