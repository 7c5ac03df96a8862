#!/usr/bin/env bash
# CLI test rk_locate_partial_turret_warns: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate
err=$(rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$d/partial.csv" 2>&1 >/dev/null)
echo "$err" | grep -q '^rk-locate: warning: .* not covered by'
echo ok
