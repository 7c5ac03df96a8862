#!/usr/bin/env bash
# CLI test rk_extract_features_nothing: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
e=$data/att_empty
hides=""
for id in belly canopy fin ltail lwing nose rwing tail; do hides="$hides --hide $id:0:5"; done
rk-sim attitude --out "$e" --force --camera "$data/att_cam.json" --range-m 40 --duration 0.3 --fps 10 --quiet $hides
"$expect" 1 "$data/att_none.csv" 'nothing detected' -- rk-extract features --video "$e/att/video.mkv" --fps 10 --target "$d/target.json" -o "$data/att_none.csv"
echo ok
