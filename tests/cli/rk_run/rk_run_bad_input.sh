#!/usr/bin/env bash
# CLI test rk_run_bad_input: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/bad; rm -rf "$d"; mkdir -p "$d"
t=$d/syntax; fresh "$t"; printf '{"name": "x",\n "cameras": {\n' > "$t/trial.json"
"$expect" 3 "$t/out" 'trial.json:[0-9]+:[0-9]+: invalid JSON' -- rk-run "$t"
t=$d/role; fresh "$t"; sed -i 's/"role": "beacon"/"role": "beakon"/' "$t/trial.json"
line=$(grep -n beakon "$t/trial.json" | cut -d: -f1)
"$expect" 3 "$t/out" "trial.json:$line:[0-9]+: cameras.az.role: 'beakon' is not one of" -- rk-run "$t"
t=$d/novideo; fresh "$t"
python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); m['cameras']['az']['video']=[]; json.dump(m,open(p,'w'),indent=1)" "$t/trial.json"
"$expect" 3 "$t/out" 'trial.json:[0-9]+:[0-9]+: cameras.az.video: must be a path or a non-empty list of paths' -- rk-run "$t"
t=$d/step; fresh "$t"; sed -i 's/"steps": {}/"steps": {"locat": {}}/' "$t/trial.json"
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: steps.locat: unknown step 'locat'" -- rk-run "$t"
t=$d/reserved; fresh "$t"; sed -i 's/"steps": {}/"steps": {"locate": {"turret": "other.csv"}}/' "$t/trial.json"
"$expect" 3 "$t/out" "steps.locate.turret: option '--turret' is set by rk-run" -- rk-run "$t"
t=$d/missing; fresh "$t"; rm "$t/az/video.mkv"
"$expect" 4 "$t/out" 'az/video.mkv: no such file' -- rk-run "$t"
"$expect" 4 - 'no such trial manifest' -- rk-run "$d/none"
"$expect" 2 - -- rk-run
"$expect" 2 - -- rk-run "$t" --jobs 0
"$expect" 2 - -- rk-run "$t" --bogus
echo ok
