#!/usr/bin/env bash
# CLI test rk_smooth_aukf_data: registered, and described, in tests/cli/rk_smooth_aukf.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/aukf; rm -rf "$d"; mkdir -p "$d"
# Turntable-like: yaw 350° + 10°/s through north (deterministic pseudo-noise), x_m with one empty
# value (partial update), one row with both empty (status predicted), and a comment line.
awk 'BEGIN { print "t_s,yaw_deg,x_m"; for (k = 0; k < 60; k++) { t = 0.05 * k;
  a = 350 + 10 * t + 0.05 * sin(7.3 * k); if (a >= 360) a -= 360;
  if (k == 20) printf "%.6f,,\n", t; else if (k == 30) printf "%.6f,%.6f,\n", t, a;
  else printf "%.6f,%.6f,%.6f\n", t, a, 2 + 0.5 * t + 0.001 * sin(3.1 * k);
  if (k == 10) print "# comment" } }' > "$d/in.csv"
sh -c "printf 't_s,yaw_deg\n0,1\n0.05,2\n'" > "$d/two.csv"
sh -c "printf 't_s,yaw_deg\n0,1\n0.05,2\n0.05,3\n0.15,4\n'" > "$d/dup.csv"
sh -c "printf 't_s,yaw_deg\n0,1\n0.1,2\n0.05,3\n0.15,4\n'" > "$d/back.csv"
sh -c "printf 't_s,yaw_deg\n0,1\n0.05,2\n0.1,abc\n0.15,4\n'" > "$d/text.csv"
echo ok
