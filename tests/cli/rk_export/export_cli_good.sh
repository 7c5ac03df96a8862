#!/usr/bin/env bash
# CLI test export_cli_good: registered, and described, in tests/cli/rk_export.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/export; o=$d/good; rm -rf "$o"; mkdir -p "$o"
check() { python3 "$src/tests/cli/rk_export/check_export.py" "$@"; }
E=2026-01-01T06:30:00Z
# The trajectory, with the trial's epoch.
rk-export kml --trajectory "$d/traj.csv" --epoch-utc "$E" -o "$o/t.kml" --report "$o/t.kml.json"
rk-export czml --trajectory "$d/traj.csv" --epoch-utc "$E" -o "$o/t.czml" --report "$o/t.czml.json"
check "$d/traj.csv" --kml "$o/t.kml" --czml "$o/t.czml" --epoch "$E"
grep -q '<TimeStamp><when>2026-01-01T06:30:0' "$o/t.kml"
python3 - "$o/t.kml.json" "$d/traj.csv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["status"] == "ok" and r["subcommand"] == "kml" and r["inputs"]["trajectory"]["path"] == sys.argv[2], r
assert r["rows_by_status"]["ok"] > 100 and r["headline"]["rows placed"]["unit"] == "fraction"
assert r["options"]["sample_interval_s"] == 1.0 and r["epoch_utc"] == "2026-01-01T06:30:00Z"
assert r["export"]["lines"] >= 1 and r["export"]["sample_placemarks"] >= 5, r["export"]
PY
# Every row as a sample, a geoid undulation, no epoch (no time stamps), --name.
rk-export kml --trajectory "$d/traj.csv" --sample-interval 0 --geoid-undulation 47.25 --extrude --name "trial <7>" -o "$o/all.kml"
check "$d/traj.csv" --kml "$o/all.kml" --geoid 47.25
grep -q '<name>trial &lt;7&gt;</name>' "$o/all.kml"
! grep -q '<TimeStamp>' "$o/all.kml"
# Two ids: a Folder and a packet each; the lost rows of 'tail' split its runs.
rk-export kml --trajectory "$d/ids.csv" --epoch-utc "$E" -o "$o/ids.kml"
rk-export czml --trajectory "$d/ids.csv" --epoch-utc "$E" -o "$o/ids.czml"
check "$d/ids.csv" --kml "$o/ids.kml" --czml "$o/ids.czml" --epoch "$E"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert [p['id'] for p in d] == ['document', 'trajectory/nose', 'trajectory/tail'], [p['id'] for p in d]; assert len(d[2]['availability']) > len(d[1]['availability'])" "$o/ids.czml"
# A located target with WGS-84 columns.
rk-export kml --located "$d/located.csv" --epoch-utc "$E" -o "$o/loc.kml"
rk-export czml --located "$d/located.csv" --epoch-utc "$E" -o "$o/loc.czml"
check "$d/located.csv" --kml "$o/loc.kml" --czml "$o/loc.czml" --epoch "$E"
# -o - is -o FILE byte for byte; stdin as the input.
rk-export czml --trajectory "$d/traj.csv" --epoch-utc "$E" -o - > "$o/stdout.czml"
cmp "$o/stdout.czml" "$o/t.czml"
rk-export kml --trajectory - --epoch-utc "$E" -o "$o/stdin.kml" < "$d/traj.csv"
check "$d/traj.csv" --kml "$o/stdin.kml" --epoch "$E"
# Without an epoch CZML says what it does: a warning, the stand-in date in the file.
rk-export czml --trajectory "$d/traj.csv" -o "$o/noepoch.czml" 2> "$o/noepoch.err"
grep -q '^rk-export: warning: no --epoch-utc: t_s = 0 is shown at 2000-01-01T00:00:00Z' "$o/noepoch.err"
check "$d/traj.csv" --czml "$o/noepoch.czml" --epoch 2000-01-01T00:00:00Z
# --bad-rows skip: a garbage row is dropped with a warning; the rest is exported as from the clean file.
{ head -3 "$d/traj.csv"; echo "garbage,row"; tail -n +4 "$d/traj.csv"; } > "$o/bad.csv"
rk-export kml --trajectory "$o/bad.csv" --bad-rows skip -o "$o/skip.kml" 2> "$o/skip.err"
grep -q 'bad.csv:4:[0-9]*: skipped bad row' "$o/skip.err"
check "$d/traj.csv" --kml "$o/skip.kml"
# A duplicated record (row 3 written twice): an error at the copy without --bad-rows skip (no output), dropped as
# "repeats" with it, the export as from the clean file.
{ head -4 "$d/traj.csv"; sed -n 4p "$d/traj.csv"; tail -n +5 "$d/traj.csv"; } > "$o/dup.csv"
"$expect" 3 "$o/dup.kml" 'dup.csv:5:1: .*time does not increase' -- rk-export kml --trajectory "$o/dup.csv" -o "$o/dup.kml"
rk-export kml --trajectory "$o/dup.csv" --bad-rows skip -o "$o/dup.kml" 2> "$o/dup.err"
grep -q 'dup.csv:5:1: skipped bad row: .*repeats' "$o/dup.err"
check "$d/traj.csv" --kml "$o/dup.kml"
echo ok
