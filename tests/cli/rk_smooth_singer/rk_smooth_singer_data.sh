#!/usr/bin/env bash
# CLI test rk_smooth_singer_data: registered, and described, in tests/cli/rk_smooth_singer.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/singer; rm -rf "$d"; mkdir -p "$d"
# 5 Hz range log, 1 m/s + 0.2 m/s^2, one device-error row (status 7) and one masked value.
awk 'BEGIN { print "t_s,range_m,status"; for (k = 0; k < 40; k++) { t = 0.2 * k;
  if (k == 10) printf "%.3f,,7\n", t; else if (k == 20) printf "%.3f,999.0,3\n", t;
  else printf "%.3f,%.6f,0\n", t, 50 + t + 0.1 * t * t } }' > "$d/range.csv"
# Located-like file: azimuth through north, elevation, tool statuses, one lost row.
awk 'BEGIN { print "frame,t_s,az_deg,el_deg,range_m,status"; for (k = 0; k < 30; k++) { t = 0.05 * k;
  a = 359 + 2 * t; if (a >= 360) a -= 360;
  if (k == 5) printf "%d,%.3f,,,,lost\n", k, t; else printf "%d,%.3f,%.6f,%.6f,%.6f,ok\n", k, t, a, 20 - t, 40 + t } }' > "$d/located.csv"
printf 't_s,range_m\n0,1\n0.1,2\n' > "$d/two.csv"
printf 't_s,range_m\n0,1\n0.1,2\n0.1,3\n0.3,4\n' > "$d/dup.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.1,3\n0.3,4\n' > "$d/back.csv"
printf 't_s,range_m\n0,1\n0.1,2\n0.2,abc\n0.3,4\n' > "$d/text.csv"
printf 't_s,range_m\n0,1\n0.1,\n0.2,\n0.3,\n0.4,5\n' > "$d/sparse.csv"
printf 't_s,range_m,status\n0,1,0\n0.1,2,0\n0.2,3,bad\n0.3,4,0\n' > "$d/badstatus.csv"
echo ok
