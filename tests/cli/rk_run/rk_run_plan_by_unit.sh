#!/usr/bin/env bash
# CLI test rk_run_plan_by_unit: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/plan_by_unit; rm -rf "$d"; mkdir -p "$d"
edit() { python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); exec(sys.argv[2]); json.dump(m,open(p,'w'),indent=1)" "$@"; }

# A step switched off: one line per unit on stderr (planned, skipped and why), the same in report.json and
# last-run.json; exit 0.
t=$d/off; fresh "$t"; edit "$t/trial.json" "m['steps']={'resample-range': False}"
rk-run "$t" --no-plots > "$d/off.out" 2> "$d/off.err"
cat "$d/off.err"
grep -qx 'rk-run: az (beacon camera): planned extract-beacon, locate, smooth; skipped resample-range (off: switched off in trial.json "steps")' "$d/off.err"
[ "$(json "$t/out/report.json" "d['units'][0]['skipped'][0]['step']")" = resample-range ]
[ "$(json "$t/last-run.json" "d['units'][0]['planned']")" = "['extract-beacon', 'locate', 'smooth']" ]
# --quiet: nothing on stderr (the lines stay in the reports).
rk-run "$t" --no-plots --quiet > /dev/null 2> "$d/quiet.err"
[ ! -s "$d/quiet.err" ]

# A theodolite trial whose manifest lists no images (no camera): says the log is not used and that there is
# nothing to run, instead of a silent "done (0 run)".
t=$d/theo_no_images; mkdir -p "$t"; cp "$data/small/turret.csv" "$t/theodolite.csv"
printf '{"name": "theo", "theodolite": "theodolite.csv"}\n' > "$t/trial.json"
rk-run "$t" 2> "$d/theo.err"; cat "$d/theo.err"
grep -q '^rk-run: theodolite (log theodolite.csv): not used: "cameras" lists no camera' "$d/theo.err"
grep -qx 'rk-run: trial (manifest): nothing to run: the manifest lists no camera and no radar' "$d/theo.err"

# A product the manifest asks for and the plan cannot make: exit 3 at the request's line:col, nothing runs.
t=$d/no_range; fresh "$t"; edit "$t/trial.json" "m['range']=None; m['steps']={'az/resample-range': {'method': 'cubic'}}"
line=$(grep -n '"az/resample-range"' "$t/trial.json" | cut -d: -f1)
"$expect" 3 "$t/out" "trial.json:$line:[0-9]+: steps.az/resample-range: asks for az/resample-range, which cannot run: the manifest has no range log" -- rk-run "$t"
[ "$(json "$t/last-run.json" "d['units'][0]['skipped'][0]['reason']")" = "not-applicable: the manifest has no range log" ]
t=$d/no_turret; fresh "$t"; edit "$t/trial.json" "m['turret']=None"
line=$(grep -n '"role"' "$t/trial.json" | cut -d: -f1)
"$expect" 3 "$t/out" "trial.json:$line:[0-9]+: cameras.az.role: a beacon camera asks for az/locate, which cannot run: the manifest has no turret or theodolite log" -- rk-run "$t"
t=$d/no_radar; fresh "$t"; edit "$t/trial.json" "m['steps']={'radar/register-batch': True}"
"$expect" 3 "$t/out" 'steps.radar/register-batch: asks for register-batch of the radar, but the manifest has no "radar" block' -- rk-run "$t"
# A radar block without nav, a silhouette camera without a target model: the manifest's own errors (exit 3).
t=$d/radar_no_nav; fresh "$t"; edit "$t/trial.json" "m['radar']={'plots': 'range.csv'}"
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: radar: missing field 'nav'" -- rk-run "$t"
t=$d/no_target; fresh "$t"; edit "$t/trial.json" "m['cameras']['az']['role']='silhouette'"
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: cameras.az: a silhouette camera needs 'target'" -- rk-run "$t"
# A chain switched off in "steps" asks for nothing: exit 0.
t=$d/chain_off; fresh "$t"; edit "$t/trial.json" "m['turret']=None; m['steps']={'locate': False}"
rk-run "$t" --no-plots 2> "$d/chain_off.err" > /dev/null; cat "$d/chain_off.err"
grep -q 'skipped locate (off: switched off in trial.json "steps"); smooth (not-applicable: needs az/locate, which is off)' "$d/chain_off.err"
echo ok
