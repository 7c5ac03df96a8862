#!/usr/bin/env bash
# CLI test rk_sim_posetrack_turntable: registered, and described, in tests/cli/rk_sim_posetrack.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
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
