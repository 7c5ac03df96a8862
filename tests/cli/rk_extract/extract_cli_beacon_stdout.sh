#!/usr/bin/env bash
# CLI test extract_cli_beacon_stdout: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract
rk-extract beacon --video "$x/beacon.mkv" --fps 20 -o - | head -n 1 | grep -qx 'frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px'
