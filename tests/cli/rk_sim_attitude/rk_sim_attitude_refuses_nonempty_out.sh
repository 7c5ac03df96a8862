#!/usr/bin/env bash
# CLI test rk_sim_attitude_refuses_nonempty_out: registered, and described, in tests/cli/rk_sim_attitude.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim attitude --out "$d" --no-video --duration 1
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.att_keep'; then echo "temporary folder left"; exit 1; fi
rk-sim attitude --out "$d" --force --no-video --duration 1 --quiet
test ! -e "$d/keep.txt"
test -s "$d/truth/pose.csv"
f=$data/att_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim attitude --out "$f/run" --no-video --duration 1
echo ok
