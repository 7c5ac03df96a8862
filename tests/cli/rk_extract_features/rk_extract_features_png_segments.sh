#!/usr/bin/env bash
# CLI test rk_extract_features_png_segments: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
p=$data/att_png
rk-sim attitude --out "$p" --force --format png --camera "$data/att_cam.json" --range-m 40 --duration 0.5 --fps 10 --quiet
test -s "$p/att/000004.png"
rk-extract features --video "$p/att/%06d.png" --video "$p/att/%06d.png" --fps 10 --t0 1 --target "$p/target.json" \
  -o "$data/att_png_points.csv" --quiet
test "$(grep -c '' "$data/att_png_points.csv")" = 81
test "$(tail -n 1 "$data/att_png_points.csv" | cut -d, -f1-3)" = "9,1.900000000,tail"
test "$(awk -F, 'NR > 1 && $6 != "ok"' "$data/att_png_points.csv" | grep -c '')" = 0
echo ok
