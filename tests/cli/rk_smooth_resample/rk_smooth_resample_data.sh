#!/usr/bin/env bash
# CLI test rk_smooth_resample_data: registered, and described, in tests/cli/rk_smooth_resample.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/resample; rm -rf "$d"; mkdir -p "$d"
# 5 Hz range log from 0.1 s to 5.9 s, range = 40 + 2 t; one device-error row (status 7, at
# 1.1 s: bridged) and a hole from 2.9 to 4.1 s (longer than the default gap limit 0.5 s).
awk 'BEGIN { print "# range log"; print "t_s,range_m,status"; for (k = 0; k < 30; k++) { t = 0.1 + 0.2 * k;
  if (t > 3.05 && t < 4.05) continue;
  if (k == 5) printf "%.3f,,7\n", t; else printf "%.3f,%.6f,0\n", t, 40 + 2 * t } }' > "$d/range.csv"
# 20 Hz frames from 0 to 6 s.
awk 'BEGIN { print "frame,t_s"; for (k = 0; k <= 120; k++) printf "%d,%.3f\n", k, 0.05 * k }' > "$d/frames.csv"
printf 'frame,time\n0,0.1\n1,0.2\n' > "$d/frames_not.csv"
printf 'frame,t_s\n0,0.1\n1,0.3\n2,0.2\n' > "$d/frames_back.csv"
printf 'frame,t_s\n0,0.1\n1,x\n' > "$d/frames_text.csv"
printf 't_s,range_m\n0,1\n0.2,2\n' > "$d/two.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.2,3\n0.4,4\n' > "$d/dup.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.4,1e\n0.6,4\n' > "$d/text.csv"
echo ok
