#!/usr/bin/env bash
# CLI test rk_calibrate_pointing_bad_input: registered, and described, in tests/cli/rk_calibrate_pointing.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
s=$data/pointing/session; d=$data/pointing/bad; rm -rf "$d"; mkdir -p "$d"; o=$d/out.json
epoch=$(python3 -c "import json;print(json.load(open('$s/trial.json'))['epoch_utc'])")
station=$(python3 -c "import json;s=json.load(open('$s/trial.json'))['station'];print('%r,%r,%r'%(s['lat_deg'],s['lon_deg'],s['h_m']))")
# Inputs with one fault each.
sed '5s/,L[0-9]*,/,NOPE,/;5s/,S[0-9]*,/,NOPE,/' "$s/points.csv" >"$d/unknown_id.csv"
sed '6s/^\([^,]*,[^,]*,[^,]*,\)[^,]*/\1abc/' "$s/points.csv" >"$d/text_x.csv"
head -n 3 "$s/points.csv" >"$d/few.csv"
head -n 40 "$s/turret.csv" >"$d/turret_short.csv"
L() { "$expect" "$@"; }
C() { rk-calibrate pointing --camera "$s/camera.json" --landmarks "$s/landmarks.csv" --station "$station" -o "$o" "$@"; }
export -f C; export s station o
L 3 "$o" 'unknown_id.csv:5:[0-9]+: unknown target id' -- C --observations "$d/unknown_id.csv" --turret "$s/turret.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --dut1 0
L 2 "$o" 'epoch-utc' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --stars "$s/stars.csv"
L 3 "$o" 'below the horizon' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --stars "$s/stars.csv" --epoch-utc 2026-03-20T15:00:00Z --dut1 0
L 3 "$o" 'points.csv:[0-9]+:1: turret log .* does not cover' -- C --observations "$s/points.csv" --turret "$d/turret_short.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --dut1 0
L 1 "$o" 'residuals, not more than' -- C --observations "$d/few.csv" --turret "$s/turret.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --dut1 0 --estimate az_offset,tilt,el_axis_tilt,mount
L 3 "$o" 'text_x.csv:6:[0-9]+:' -- C --observations "$d/text_x.csv" --turret "$s/turret.csv" --stars "$s/stars.csv" --epoch-utc "$epoch" --dut1 0
L 2 "$o" 'unknown term' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --estimate az_offset,zoom
L 2 "$o" 'station' -- rk-calibrate pointing --camera "$s/camera.json" --landmarks "$s/landmarks.csv" --station 32,1 -o "$o" --observations "$s/points.csv" --turret "$s/turret.csv"
L 2 "$o" 'epoch-utc' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --stars "$s/stars.csv" --epoch-utc yesterday
L 4 "$o" 'no_such.csv' -- C --observations "$d/no_such.csv" --turret "$s/turret.csv"
L 2 "$o" '--pressure-hpa' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --pressure-hpa -3
L 2 - 'refusing to overwrite' -- C --observations "$s/points.csv" --turret "$s/turret.csv" --camera-out "$s/camera.json"
echo ok
