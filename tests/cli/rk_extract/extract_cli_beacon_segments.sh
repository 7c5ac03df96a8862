#!/usr/bin/env bash
# CLI test extract_cli_beacon_segments: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract
rk-extract beacon --video "$x/beacon.mkv" --video "$x/beacon.mkv" --fps 20 -o - | awk -F, 'NR>1{n++} END{exit n!=120}'
