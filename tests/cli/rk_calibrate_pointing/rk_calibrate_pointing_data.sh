#!/usr/bin/env bash
# CLI test rk_calibrate_pointing_data: registered, and described, in tests/cli/rk_calibrate_pointing.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/pointing
rm -rf "$d"; mkdir -p "$d"
rk-sim pointing --out "$d/session" --seed 4 --landmarks 8 --stars 10 --dwell 1 --fps 5 --report "$d/sim_report.json"
for f in trial.json turret.csv points.csv landmarks.csv stars.csv camera.json truth/pointing.json truth/camera.json; do
  test -s "$d/session/$f"
done
grep -q '^frame,t_s,id,x_px,y_px' "$d/session/points.csv"
echo ok
