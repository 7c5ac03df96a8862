#!/usr/bin/env bash
# CLI test rk_sim_posetrack_refuses_nonempty_out: registered, and described, in tests/cli/rk_sim_posetrack.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/pt_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim posetrack --out "$d" --scenario head
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.pt_keep'; then echo "temporary folder left"; exit 1; fi
rk-sim posetrack --out "$d" --force --duration 1
test ! -e "$d/keep.txt"
test "$(grep -c '' "$d/measurements.csv")" = 22
echo ok
