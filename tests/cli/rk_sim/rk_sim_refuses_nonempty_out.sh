#!/usr/bin/env bash
# CLI test rk_sim_refuses_nonempty_out: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/sim_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim beacon --out "$d" --preset small --duration 0.5
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
test "$(cat "$d/keep.txt")" = precious || { echo "file changed"; exit 1; }
if ls -A "$data" | grep -q '^\.sim_keep'; then echo "temporary folder left"; exit 1; fi
# With --force it is replaced as a whole.
rk-sim beacon --out "$d" --force --preset small --duration 0.5 --format png
test ! -e "$d/keep.txt"
test -s "$d/trial.json"
if ls -A "$data" | grep -q '^\.sim_keep'; then echo "old folder left"; exit 1; fi
echo ok
