#!/usr/bin/env bash
# CLI test rk_sim_unwritable_out: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
f=$data/sim_file; echo x > "$f"
"$expect" 4 "$f/trial" -- rk-sim beacon --out "$f/trial" --preset small --duration 0.5
"$expect" 4 - -- rk-sim beacon --out /proc/rk_sim_nowhere/trial --preset small --duration 0.5
echo ok
