#!/usr/bin/env bash
# CLI test rk_sim_radar_refuses_nonempty_out: registered, and described, in tests/cli/rk_sim_radar.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/radar_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim radar --out "$d" --steps 2
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.radar_keep'; then echo "temporary folder left"; exit 1; fi
f=$data/radar_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim radar --out "$f/run" --steps 2
echo ok
