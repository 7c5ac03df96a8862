#!/usr/bin/env bash
# CLI test rk_extract_points_bad: registered, and described, in tests/cli/rk_extract_points.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/points_small
o=$data/points_bad.csv; rm -f "$o"
s=$data/seeds_bad.csv
run() { "$expect" "$@"; }
cmd=(rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" --seeds "$s" -o "$o")
printf 'id,frame,x_px,y_px,method\nq1,0,100,100,quadrant\nb1,0,50,50,blob\n' > "$s"
run 3 "$o" 'seeds_bad.csv:3:12: .*unknown method' -- "${cmd[@]}"
printf 'id,frame,x_px,y_px,method\nq1,0,100,100,quadrant\nq1,0,101,100,quadrant\n' > "$s"
run 3 "$o" 'seeds_bad.csv:3:1: .*seeded twice at frame 0' -- "${cmd[@]}"
printf 'id,frame,x_px,y_px,method\nq1,0,100,100,quadrant\nc1,0,700,100,circle\n' > "$s"
run 3 "$o" 'seeds_bad.csv:3:6: .*outside the 640x480 image' -- "${cmd[@]}"
printf 'id,frame,x_px,y_px,method\nq1,0,100,100,quadrant\nq1,5000,100,100,quadrant\n' > "$s"
run 3 "$o" 'seeds_bad.csv:3:4: .*past the end of the recording \(100 frames\)' -- "${cmd[@]}"
# Streaming to stdout: a seed past the end is found before any row goes out.
run 3 - 'seeds_bad.csv:3:4: .*past the end' -- rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" \
  --seeds "$s" -o -
printf 'id,frame,x_px,y_px,method\nq1,0,100,x,quadrant\n' > "$s"
run 3 "$o" 'seeds_bad.csv:2:10:' -- "${cmd[@]}"
run 2 "$o" 'seeds' -- rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" -o "$o"
run 4 "$o" 'no_such_seeds.csv' -- rk-extract points --video "$d/video.mkv" --frames "$d/frames.csv" \
  --seeds "$data/no_such_seeds.csv" -o "$o"
run 2 "$o" 'ncc-min' -- "${cmd[@]}" --ncc-min 2
echo ok
