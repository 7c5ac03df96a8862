#!/usr/bin/env bash
# CLI test rk_locate_report_typed_warnings: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate
w=$(mktemp -d "${TMPDIR:-/tmp}/rk_typed.XXXXXX")
trap 'rm -rf "$w"' EXIT
# A turret log that covers part of the video (a warning on stderr) and a track with one unreadable row
# (skipped under --bad-rows skip): both must be typed warnings in the report, the stderr one word for word.
{ head -n 3 "$d/track.csv"; echo "2,not-a-time,1,2,ok"; tail -n +4 "$d/track.csv"; } > "$w/track.csv"
err=$(rk-locate --track "$w/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --bad-rows skip \
      -o "$w/located.csv" --report "$w/report.json" 2>&1 >"$w/stdout.txt")
python3 - "$w/report.json" "$w/located.csv" "$err" <<'PY'
import csv, json, sys
rep = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
stderr = [l.split("warning: ", 1)[1] for l in sys.argv[3].splitlines() if "warning: " in l]
codes = {w["code"]: w["message"] for w in rep["warnings"]}
assert all(set(w) >= {"code", "message"} for w in rep["warnings"]), rep["warnings"]
assert "rows_skipped" in codes, codes
assert any(m in stderr for m in codes.values()), (codes, stderr)
by = rep["rows_by_status"]
assert sum(by.values()) == len(rows), (by, len(rows))
for s in ("ok", "predicted", "lost", "reacquired", "invalid"):
    assert by[s] == sum(1 for r in rows if r["status"] == s), (s, by)
assert rep["termination"] == "completed", rep["termination"]
assert rep["headline"] and all("value" in f for f in rep["headline"].values()), rep["headline"]
PY
echo ok
