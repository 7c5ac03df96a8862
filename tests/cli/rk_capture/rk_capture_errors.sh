#!/usr/bin/env bash
# CLI test rk_capture_errors: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_capture/lib.sh"
d=$data/capture_err; rm -rf "$d"; mkdir -p "$d"; cd "$d"
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48"}]}' > ok.json
"$expect" 2 out1 'config is required' -- rk-capture --out out1
"$expect" 2 - 'unknown|extra|not expected|The following' -- rk-capture --config ok.json --out out1 --bogus
"$expect" 4 out1 'missing.json' -- rk-capture --config missing.json --out out1
printf '{"cameras": [\n  {"name": "az",,}\n]}\n' > syntax.json
"$expect" 3 out1 'syntax.json:2:' -- rk-capture --config syntax.json --out out1
echo '{"rangefinder": {"port": "/dev/null", "parity": "mark"}}' > parity.json
"$expect" 3 out1 "parity.json: rangefinder: 'parity'" -- rk-capture --config parity.json --out out1
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48", "fps": -1}]}' > fps.json
"$expect" 3 out1 "fps" -- rk-capture --config fps.json --out out1 --quiet
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48"}], "rangefinder": {"port": "nothere"}}' > port.json
"$expect" 4 out1 'nothere' -- rk-capture --config port.json --out out1 --quiet
mkdir keep; echo precious > keep/file
"$expect" 2 - 'not empty' -- rk-capture --config ok.json --out keep --quiet
test "$(cat keep/file)" = precious && test "$(ls keep)" = file
"$expect" 2 - 'duration' -- rk-capture --config ok.json --out out1 --duration -1 --quiet
test ! -e out1
# recover: not a trial (4), a trial with unreadable data (3), usage (2)
mkdir empty
"$expect" 4 - 'trial.json' -- rk-capture recover empty
"$expect" 2 - 'recover takes' -- rk-capture --config ok.json recover empty
rk-capture --config ok.json --out t --duration 0.6 --quiet
printf 'oops\n' >> t/az/frames.csv && printf '9,1.0,1,1,9,0\n' >> t/az/frames.csv
"$expect" 3 - 'frames.csv:' -- rk-capture recover t
# rk-sim device: bad fault, missing kind
"$expect" 2 - 'fault' -- rk-sim device dimetix --fault bogus:1:1 --duration 1
"$expect" 2 - '' -- rk-sim device
echo ok
