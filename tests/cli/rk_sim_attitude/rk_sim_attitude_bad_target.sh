#!/usr/bin/env bash
# CLI test rk_sim_attitude_bad_target: registered, and described, in tests/cli/rk_sim_attitude.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
printf '{"points": {"a": [0,0,0], "b": [1,0,0], "c": [2,0,0], "d": [3,0,0]}}' > "$data/att_line.json"
"$expect" 3 "$data/att_bad5" 'att_line.json.*collinear' -- rk-sim attitude --out "$data/att_bad5" --target "$data/att_line.json" --no-video
echo ok
