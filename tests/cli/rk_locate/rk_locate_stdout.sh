#!/usr/bin/env bash
# CLI test rk_locate_stdout: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate
rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o - 2>/dev/null > "$d/stdout.csv"
head -1 "$d/stdout.csv" | grep -q '^frame,t_s,az_deg,el_deg,range_m'
grep -q ',ok,none,' "$d/stdout.csv"   # no range log: range_status none
# stdin for the track
cat "$d/track.csv" | rk-locate --track - --camera "$d/camera.json" --turret "$d/turret.csv" -o - -q | cmp - "$d/stdout.csv"
echo ok
