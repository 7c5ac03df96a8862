#!/usr/bin/env bash
# CLI test rk_extract_features_16bit: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
p=$data/att_16
rk-sim attitude --out "$p" --force --bit-depth 16 --camera "$data/att_cam.json" --range-m 40 --duration 0.5 --fps 10 --quiet
rk-extract features --video "$p/att/video.mkv" --frames "$p/att/frames.csv" --target "$p/target.json" -o "$data/att_16_points.csv" --quiet
python3 "$src/bench/attitude_points_stats.py" "$data/att_16_points.csv" "$p/truth/points.csv" | tee "$data/att_16_stats.txt"
grep -q "identity errors 0  status {'ok': 40}" "$data/att_16_stats.txt"
awk '/rms/ { if ($7 > 0.05 || $14 > 0.05) exit 1 }' "$data/att_16_stats.txt"
echo ok
