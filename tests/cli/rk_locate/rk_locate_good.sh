#!/usr/bin/env bash
# CLI test rk_locate_good: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" \
  -o "$o/located.csv" --report "$o/report.json" --quiet
head -1 "$o/located.csv" | grep -qx 'frame,t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,range_status,boresight_az_deg,boresight_el_deg,sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,sigma_u_m,corr_az_el'
test "$(grep -c '' "$o/located.csv")" = 25
grep -q '^7,0.370000000,,,,,,,lost,,' "$o/located.csv"          # lost row kept, empty values
grep -q '^0,0.020000000,359\.[0-9]*,29\.9[0-9]*,80\.010000,' "$o/located.csv"  # az before north, range at 0.02 s
grep -q '^12,0.620000000,0\.[0-9]*,30\.[0-9]*,,,,,ok,device_error,' "$o/located.csv"
grep -q '^20,1.020000000,,,,,,,invalid,,,' "$o/located.csv"      # frames after the turret log (t > 1.0 s)
test "$(grep -c ',invalid,' "$o/located.csv")" = 4
grep -q '"range_coverage"' "$o/report.json"
grep -q '"turret_interp": "cubic"' "$o/report.json"
# Located row 0: the track pixel is the principal point plus distortion/mount:
# compare with the analysis tool against itself (zero error).
rk-analyze compare --estimate "$o/located.csv" --reference "$o/located.csv" --columns az_deg -o "$o/self.json"
grep -q '"rms": 0.0' "$o/self.json"
echo ok
