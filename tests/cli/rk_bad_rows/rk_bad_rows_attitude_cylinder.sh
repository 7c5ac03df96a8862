#!/usr/bin/env bash
# CLI test rk_bad_rows_attitude_cylinder: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
T=$data/theo_trial; w=$data/bad_rows/cylinder; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$T/points.csv" x_px)
nu=$(dirty_in "$w" "$T/theodolite.csv" el_deg)
a=(--camera "$T/theo/camera.json" --target "$T/target.json")
skip_same "$w" points "$np" theodolite "$nu" -- rk-attitude cylinder --points @points.csv --theodolite @theodolite.csv "${a[@]}"
"$expect" 3 "$w/x.csv" 'theodolite.csv:[0-9]+:[0-9]+:' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$w/theodolite.csv" "${a[@]}" -o "$w/x.csv"
echo ok
