#!/usr/bin/env bash
# CLI test rk_attitude_oi_boresight_stdout: registered, and described, in tests/cli/rk_attitude_oi.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --boresight 30,3 -o - | awk -F, 'NR > 1 && $9 == "ok" { n++ } END { exit n != 10 }'
rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
  --turret "$d/turret.csv" --pure-oi -o - | awk -F, 'NR > 1 && $9 == "ok" { n++ } END { exit n != 10 }'
echo ok
