#!/usr/bin/env bash
# CLI test rk_sim_theodolite_trial: registered, and described, in tests/cli/rk_sim_theodolite.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
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
