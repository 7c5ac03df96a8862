#!/usr/bin/env bash
# CLI test rk_run_silhouette_cylinder: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
other_unit rk_run_silhouette_cylinder "extract-silhouette attitude-cylinder" theodolite --images png --sensor-px 640 --duration 0.5 --speed-mps 50 --track-error-px 10
# Issue 20: attitude-cylinder runs the image fit on the trial's frames by default, and the report says so;
# "image-fit": false re-runs that step alone with the three-point solve (the video no longer read).
t=$data/run/rk_run_silhouette_cylinder
q="[s for s in d['steps'] if s['id'] == 'theo/attitude-cylinder'][0]"
[ "$(json "$t/out/report.json" "$q['quality']['method']")" = image-fit ]
[ "$(json "$t/out/report.json" "'--video' in $q['command_line']")" = True ]
[ "$(json "$t/out/report.json" "$q['quality']['image_fit']['fits'] > 0")" = True ]
rk-run "$t" --no-plots --dry-run 2>&1 >/dev/null | grep -q 'theo (silhouette camera): planned extract-silhouette, attitude-cylinder (image-fit)'
python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); m['steps']={'attitude-cylinder': {'image-fit': False}}; json.dump(m,open(p,'w'))" "$t/trial.json"
rk-run "$t" --no-plots > "$t.off.out"; cat "$t.off.out"
grep -Eq '^theo/extract-silhouette +skipped' "$t.off.out"
grep -Eq '^theo/attitude-cylinder +ok .*input no longer read: theo/%06d.png' "$t.off.out"
[ "$(json "$t/out/report.json" "$q['quality']['method']")" = three-point ]
[ "$(json "$t/out/report.json" "'image_fit' in $q['quality']")" = False ]
echo ok
