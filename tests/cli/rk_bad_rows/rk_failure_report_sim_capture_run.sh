#!/usr/bin/env bash
# CLI test rk_failure_report_sim_capture_run: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
w=$data/bad_rows/misc; rm -rf "$w"; mkdir -p "$w/trial"
printf '{"width_px": 640, "height_px": [' > "$w/bad.json"
fails 3 "$w/s3.json" "$w/sim3" "$w/bad.json" -- rk-sim beacon --out "$w/sim3" --camera "$w/bad.json" --duration 1 --report "$w/s3.json"
fails 2 "$w/s2.json" "$w/sim2" -- rk-sim beacon --out "$w/sim2" --bogus --report "$w/s2.json"
# (rk-sim checks that --camera exists while parsing: exit 2; its I/O error is an output it cannot write.)
fails 2 "$w/s2c.json" "$w/sim2" -- rk-sim beacon --out "$w/sim2" --camera "$w/no_such.json" --duration 1 --report "$w/s2c.json"
fails 4 "$w/s4.json" "$w/bad.json/sim4" -- rk-sim beacon --out "$w/bad.json/sim4" --duration 1 --report "$w/s4.json"
fails 3 "$w/c3.json" "$w/cap3" "$w/bad.json" -- rk-capture --config "$w/bad.json" --out "$w/cap3" --duration 1 --report "$w/c3.json"
fails 2 "$w/c2.json" "$w/cap2" -- rk-capture --config "$w/bad.json" --report "$w/c2.json"
fails 4 "$w/c4.json" "$w/cap4" -- rk-capture --config "$w/no_such.json" --out "$w/cap4" --duration 1 --report "$w/c4.json"
cp "$w/bad.json" "$w/trial/trial.json"
fails 3 "$w/r3.json" "$w/trial/out" -- rk-run "$w/trial" --report "$w/r3.json"
# The summary rk-run wrote names the manifest; the failure report does not list it twice.
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); n = sum(1 for v in r["inputs"].values() if v == sys.argv[2] or (isinstance(v, dict) and v.get("path") == sys.argv[2])); assert n == 1, r["inputs"]' \
  "$w/r3.json" "$w/trial/trial.json"
fails 2 "$w/r2.json" "$w/trial/out" -- rk-run "$w/trial" --jobs 0 --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/trial/out" -- rk-run "$w/no_such_trial" --report "$w/r4.json"
echo ok
