#!/usr/bin/env bash
# CLI test rk_sim_servo_hold_report: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/sim_hold; rm -rf "$d" "$d.json"
rk-sim beacon --out "$d" --preset small --duration 1 --servo-hold 0.3:0.2 --report "$d.json" --quiet
python3 -c "import json,sys; h=json.load(open(sys.argv[1]))['options']['servo_holds']; sys.exit(h != [{'start_s': 0.3, 'duration_s': 0.2}])" "$d.json"
echo ok
