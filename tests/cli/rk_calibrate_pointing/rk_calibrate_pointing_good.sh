#!/usr/bin/env bash
# CLI test rk_calibrate_pointing_good: registered, and described, in tests/cli/rk_calibrate_pointing.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
s=$data/pointing/session; o=$data/pointing/good; rm -rf "$o"; mkdir -p "$o"
epoch=$(python3 -c "import json;print(json.load(open('$s/trial.json'))['epoch_utc'])")
station=$(python3 -c "import json;s=json.load(open('$s/trial.json'))['station'];print('%r,%r,%r'%(s['lat_deg'],s['lon_deg'],s['h_m']))")
rk-calibrate pointing --observations "$s/points.csv" --turret "$s/turret.csv" --camera "$s/camera.json" \
  --landmarks "$s/landmarks.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --station "$station" --dut1 0 \
  --estimate az_offset,tilt,el_axis_tilt,mount,focal,time_offset -o "$o/pointing.json" --camera-out "$o/camera.json" \
  --plot "$o/residuals.png" --report "$o/report.json" 2>"$o/stderr.txt"
test -s "$o/residuals.png"
python3 - "$o" "$s" <<'PY'
import json, sys
o, s = sys.argv[1], sys.argv[2]
p = json.load(open(o + '/pointing.json')); t = json.load(open(s + '/truth/pointing.json'))
c = json.load(open(o + '/camera.json')); ct = json.load(open(s + '/truth/camera.json'))
for k in ('az_offset_deg', 'tilt_north_deg', 'tilt_east_deg', 'el_axis_tilt_deg'):
    err = (p[k] - t.get(k, 0.0) + 180) % 360 - 180
    assert abs(err) < 5 * p['sigma'][k], (k, err, p['sigma'][k])
sig = c['calibration']['sigma']
assert set(sig['mount_deg']) == {'yaw', 'pitch', 'roll'}, sig
for k in ('yaw', 'pitch', 'roll'):
    err = c['mount_deg'][k] - ct['mount_deg'][k]
    assert abs(err) < 5 * sig['mount_deg'][k], (k, err)
assert abs(c['focal_length_mm'] - ct['focal_length_mm']) < 5 * sig['focal_length_mm']
assert abs(c['time_offset_s'] - ct['time_offset_s']) < 5 * sig['time_offset_s']
n = len(p['correlation']['parameters']); assert n == 9 and len(p['correlation']['matrix']) == n
assert p['observations'] == len(p['residuals']) and p['observations_used'] > 100
r = json.load(open(o + '/report.json')); assert r['summary']['observations'] == p['observations']
print('ok', p['az_offset_deg'], p['sigma'])
PY
# No --dut1 with stars: a warning on stderr, still exit 0.
rk-calibrate pointing --observations "$s/points.csv" --turret "$s/turret.csv" --camera "$s/camera.json" \
  --landmarks "$s/landmarks.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --station "$station" -o "$o/p2.json" 2>"$o/stderr2.txt"
grep -q 'dut1' "$o/stderr2.txt"
# A row without a measured position (empty pixel) is left out with a warning and counted in the report: the fit
# uses the same observations as without it (issue 28 item 3: the one image-points reader).
python3 - "$s/points.csv" "$o/points_lost.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = dict(rows[-1])
last["frame"] = str(int(last["frame"]) + 1); last["x_px"] = ""; last["y_px"] = ""
w = csv.DictWriter(open(sys.argv[2], "w", newline=""), fieldnames=list(rows[0].keys()))
w.writeheader(); w.writerows(rows + [last])
PY
rk-calibrate pointing --observations "$o/points_lost.csv" --turret "$s/turret.csv" --camera "$s/camera.json" \
  --landmarks "$s/landmarks.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --station "$station" --dut1 0 \
  -o "$o/p3.json" --report "$o/r3.json" 2>"$o/stderr3.txt"
grep -q '1 rows of .*points_lost.csv have no measured position' "$o/stderr3.txt"
python3 - "$o" <<'PY'
import json, sys
o = sys.argv[1]
r = json.load(open(o + '/r3.json')); p3 = json.load(open(o + '/p3.json')); p2 = json.load(open(o + '/p2.json'))
assert r['observations_unmeasured'] == 1, r['observations_unmeasured']
assert 'rows_not_measured' in [w['code'] for w in r['warnings']], r['warnings']
assert p3['observations'] == p2['observations'], (p3['observations'], p2['observations'])
PY
echo ok
