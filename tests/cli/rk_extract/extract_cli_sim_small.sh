#!/usr/bin/env bash
# CLI test extract_cli_sim_small: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract; h=$src/tests/cli/rk_extract
rk-extract beacon --video "$data/small/az/video.mkv" --frames "$data/small/az/frames.csv" -o "$x/sim_track.csv" --quiet
sh "$h/check_sim.sh" "$x/sim_track.csv" "$data/small/truth/beacon.csv"
