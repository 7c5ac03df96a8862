#!/usr/bin/env bash
# CLI test export_cli_bad_input: registered, and described, in tests/cli/rk_export.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/export; b=$d/bad; rm -rf "$b"; mkdir -p "$b"
o=$b/out.kml; c=$b/out.czml
L() { "$expect" "$@"; }
h='t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status'
printf 't_s,lat_deg,lon_deg,h_m,status\n0,47,8,400,ok\n' > "$b/nocol.csv"
printf '%s\n0.0,1,2,3,47,8,400,0.1,0.1,0.1,2,ok\n0.1,1,2,3,47,8,400,0.1,0.1,0.1,2,okay\n' "$h" > "$b/status.csv"
printf '%s\n0.0,1,2,3,47,8,400,0.1,0.1,0.1,2,ok\n0.1,1,2,3,,8,400,0.1,0.1,0.1,2,ok\n' "$h" > "$b/nopos.csv"
printf '%s\n0.0,1,2,3,47,8,400,0.1,0.1,0.1,2,ok\n0.1,1,2,3,47,8x,400,0.1,0.1,0.1,2,ok\n' "$h" > "$b/text.csv"
printf '%s\n0.0,,,,,,,,,,1,lost\n0.1,,,,,,,,,,0,invalid\n' "$h" > "$b/lost.csv"
printf 't_s,az_deg,el_deg,range_m,status\n0.0,10,5,1000,ok\n' > "$b/noloc.csv"
L 3 "$o" 'nocol.csv:1:1: missing column .e_m.' -- rk-export kml --trajectory "$b/nocol.csv" -o "$o"
L 3 "$c" 'status.csv:3:[0-9]+: .*unknown status' -- rk-export czml --trajectory "$b/status.csv" -o "$c"
L 3 "$o" "nopos.csv:3:11: .*empty, but the row's status 'ok' has a position" -- rk-export kml --trajectory "$b/nopos.csv" -o "$o"
L 3 "$o" 'text.csv:3:14:' -- rk-export kml --trajectory "$b/text.csv" -o "$o"
L 3 "$c" 'noloc.csv:1:1: no WGS-84 columns lat_deg, lon_deg, h_m' -- rk-export czml --located "$b/noloc.csv" -o "$c"
L 1 "$o" 'lost.csv: no row has a position to export \(2 rows, 1 lost, 1 invalid\)' -- rk-export kml --trajectory "$b/lost.csv" -o "$o"
L 2 "$o" 'exactly one of --trajectory and --located' -- rk-export kml -o "$o"
L 2 "$o" 'exactly one of --trajectory and --located' -- rk-export kml --trajectory "$d/traj.csv" --located "$d/located.csv" -o "$o"
L 2 "$o" "epoch-utc '2026-13-01T00:00:00Z'" -- rk-export kml --trajectory "$d/traj.csv" --epoch-utc 2026-13-01T00:00:00Z -o "$o"
L 2 "$o" -- rk-export kml --trajectory "$d/traj.csv" --epoch-utc 2026-01-01T00:00:00+01:00 -o "$o"
L 2 "$o" 'sample-interval must be finite and >= 0' -- rk-export kml --trajectory "$d/traj.csv" --sample-interval -1 -o "$o"
L 2 "$o" 'geoid-undulation must be in' -- rk-export kml --trajectory "$d/traj.csv" --geoid-undulation 500 -o "$o"
L 2 "$c" 'point-size' -- rk-export czml --trajectory "$d/traj.csv" --point-size 0 -o "$c"
L 2 "$o" -- rk-export kml --trajectory "$d/traj.csv" --samples 3 -o "$o"
L 2 "$o" -- rk-export --trajectory "$d/traj.csv" -o "$o"
L 2 - 'refusing to overwrite|name the same file' -- rk-export kml --trajectory "$d/traj.csv" -o "$d/traj.csv"
head -1 "$d/traj.csv" | grep -q '^t_s,e_m'   # the input untouched
L 4 "$o" 'no_such.csv' -- rk-export kml --trajectory "$b/no_such.csv" -o "$o"
L 4 - -- rk-export kml --trajectory "$d/traj.csv" -o "$b/no_dir/x.kml"
# A failed run still writes its report (status failed, exit code).
L 3 "$o" -- rk-export kml --trajectory "$b/status.csv" -o "$o" --report "$b/failed.json"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['status']=='failed' and r['exit_code']==3, r" "$b/failed.json"
echo ok
