#!/usr/bin/env bash
# CLI test rk_run_features_oi: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
other_unit rk_run_features_oi "extract-features attitude-oi" attitude --camera "$data/att_cam.json" --range-m 40 --duration 1 --fps 10
