#!/usr/bin/env bash
# CLI test rk_attitude_cylinder_stdio: registered, and described, in tests/cli/rk_attitude_cylinder.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/att_cyl; mkdir -p "$W"
rk-attitude cylinder --points - --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" --target "$T/target.json" \
  -o - --quiet < "$T/points.csv" | awk -F, 'NR > 1 && $5 == "ok" { n++ } END { exit n != 5 }'
echo ok
