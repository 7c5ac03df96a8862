#!/usr/bin/env bash
# CLI test rk_sim_theodolite_unwritable_out: registered, and described, in tests/cli/rk_sim_theodolite.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
f=$data/theo_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim theodolite --out "$f/run"
echo ok
