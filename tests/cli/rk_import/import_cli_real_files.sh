#!/usr/bin/env bash
# CLI test import_cli_real_files: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
real=${RK_REAL_DATA:-$src/../shared/data/real}
if [ ! -f "$real/ball_12bit.mraw" ] || [ ! -f "$real/chart1.cine" ]; then
  echo "SKIP: the real recordings are not in $real"
  exit 77
fi
d=$data/import/real
mkdir -p "$d"
# Photron: 15 frames, t_s from the first frame at 1/30000 s, nominal, exposure 20 µs, camera_ts_s = frame number / rate.
rk-import frames --video "$real/ball_12bit.mraw" -o "$d/ball.csv" --report "$d/ball.json"
head -3 "$d/ball.csv"
/usr/bin/python3 - "$d/ball.csv" "$d/ball.json" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert len(rows) == 15, len(rows)
for k, r in enumerate(rows):
    assert int(r["frame"]) == k
    assert abs(float(r["t_s"]) - k / 30000) < 1e-9, r
    assert r["time_source"] == "nominal", r
    assert abs(float(r["exposure_s"]) - 20e-6) < 1e-12, r
    assert abs(float(r["camera_ts_s"]) - (52 + k) / 30000) < 1e-9, r
rep = json.load(open(sys.argv[2]))
assert rep["status"] == "ok" and rep["frame_times"]["time_sources"] == {"nominal": 15}, rep["frame_times"]
PY
# Phantom: one frame; its time block (not IRIG: camera) against an epoch of 2000-07-13; the trigger time disagrees.
rk-import frames --video "$real/chart1.cine" --epoch-utc 2000-07-13T00:00:00Z -o "$d/chart.csv" --report "$d/chart.json" 2> "$d/chart.err"
cat "$d/chart.err" "$d/chart.csv"
grep -q "warning: .*chart1.cine: the time block .* and the header's trigger time (2014-07-14" "$d/chart.err"
/usr/bin/python3 - "$d/chart.csv" "$d/chart.json" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert len(rows) == 1
r = rows[0]
# 963484684 s UTC = 2000-07-13T10:38:04Z: 38284 s after the epoch, plus the fraction 0x528c7b93 / 2^32 without
# its two flag bits.
assert r["time_source"] == "camera", r
assert abs(float(r["t_s"]) - (38284 + 0x528C7B90 / 2**32)) < 1e-9, r
assert abs(float(r["exposure_s"]) - 85907195 / 2**32) < 1e-9, r
rep = json.load(open(sys.argv[2]))
assert [w["code"] for w in rep["warnings"]] == ["times_disagree"], rep["warnings"]
PY
echo PASS
