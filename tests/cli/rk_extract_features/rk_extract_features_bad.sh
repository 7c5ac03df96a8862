#!/usr/bin/env bash
# CLI test rk_extract_features_bad: registered, and described, in tests/cli/rk_extract_features.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
o=$data/att_bad_points.csv; rm -f "$o"
"$expect" 2 "$o" 'epoch-utc' -- rk-extract features --video "$d/att/video.mkv" --epoch-utc yesterday --target "$d/target.json" -o "$o"
"$expect" 2 "$o" 'target' -- rk-extract features --video "$d/att/video.mkv" --fps 10 -o "$o"
"$expect" 2 - 'input' -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$d/target.json"
printf '{"length_m": 1.2, "diameter_m": 0.2}' > "$data/att_cyl.json"
"$expect" 3 "$o" "att_cyl.json.*points" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$data/att_cyl.json" -o "$o"
printf '{"points": {"a": [0,0,0], "b": [1,0' > "$data/att_trunc.json"
"$expect" 3 "$o" "att_trunc.json:1:" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$data/att_trunc.json" -o "$o"
head -n 6 "$d/att/frames.csv" > "$data/att_frames_short.csv"
"$expect" 3 "$o" "att_frames_short.csv" -- rk-extract features --video "$d/att/video.mkv" --frames "$data/att_frames_short.csv" --target "$d/target.json" -o "$o"
"$expect" 4 "$o" -- rk-extract features --video "$data/no_such_video.mkv" --fps 10 --target "$d/target.json" -o "$o"
"$expect" 2 "$o" 'polarity' -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$o" --polarity grey
"$expect" 2 "$o" -- rk-extract features --video "$d/att/video.mkv" --fps 10 --target "$d/target.json" -o "$o" --gate 0.9
test ! -e "$d/target.json.tmp"
echo ok
