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
echo ok
