#!/usr/bin/env bash
# CLI test extract_cli_beacon_seq16_fps: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract; h=$src/tests/cli/rk_extract
rk-extract beacon --video "$x/seq/%06d.png" --fps 20 --t0 0 -o "$x/track16.csv"
sh "$h/check_track.sh" "$x/track16.csv" 60 0 0.02
