#!/usr/bin/env bash
# CLI test rk_bad_rows_attitude: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/att_small; w=$data/bad_rows/attitude; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$d/truth/points.csv" y_px)
nu=$(dirty_in "$w" "$d/turret.csv" az_deg)
a=(--camera "$d/att/camera.json" --target "$d/target.json")
skip_same "$w" points "$np" turret "$nu" -- rk-attitude oi --points @points.csv --turret @turret.csv "${a[@]}"
"$expect" 3 "$w/x.csv" 'points.csv:4:[0-9]+:' -- rk-attitude oi --points "$w/points.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$w/points.csv" -- rk-attitude oi --points "$w/points.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-attitude oi --points "$d/truth/points.csv" --turret "$d/turret.csv" --boresight 10,5 "${a[@]}" -o "$w/x.csv" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-attitude oi --points "$w/no_such.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv" --report "$w/r4.json"
echo ok
