#!/usr/bin/env bash
# CLI tests extract_cli_sim_reversal_g<N>: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract; h=$src/tests/cli/rk_extract
# $4 = number of glints (distractors) in view.
glints=$4; d=$x/reversal_g$glints
rk-sim beacon --out "$d" --force --preset small --duration 4 --seed 5 --servo-hold 1.5:0.4 --occlusion 1.7:0.5 --distractors "$glints" --quiet
rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --quiet
sh "$h/check_return.sh" "$d/track.csv" "$d/truth/beacon.csv"
