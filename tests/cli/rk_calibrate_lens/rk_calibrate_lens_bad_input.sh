#!/usr/bin/env bash
# CLI test rk_calibrate_lens_bad_input: registered, and described, in tests/cli/rk_calibrate_lens.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
D=/usr/share/doc/opencv-doc/examples/data
W=$data/cal_lens_bad; rm -rf "$W"; mkdir -p "$W/blank" "$W/seq"
o=$W/camera.json; p=$W/plot.png; r=$W/rep.json; rm -f "$o" "$p" "$r"
board=(--board chessboard --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0.006)
# Three grey images: no board anywhere -> 1.
ffmpeg -v error -nostdin -y -f lavfi -i "nullsrc=s=160x120,format=gray,geq=lum=128" -frames:v 3 "$W/blank/%02d.png"
"$expect" 1 "$o" 'no chessboard of 9x6 found in any of the 3 images' -- \
  rk-calibrate lens --images "$W/blank/%02d.png" "${board[@]}" -o "$o" --plot "$p"
test ! -e "$p"
# Two views with a board: fewer than --min-views 3 -> 1, naming the counts; the report says failed.
cp "$D/left01.jpg" "$W/seq/01.jpg"; cp "$D/left02.jpg" "$W/seq/02.jpg"
"$expect" 1 "$o" 'only 2 usable views.*at least 3' -- rk-calibrate lens --images "$W/seq/%02d.jpg" "${board[@]}" -o "$o" --report "$r"
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); assert r["status"] == "failed" and r["exit_code"] == 1, r' "$r"
rm -f "$r"
# Unreadable image: a missing file -> 4; a file that is not an image -> 3 (SPEC.md §4: a path that cannot be
# read is an I/O error, content that cannot be decoded is invalid data). The report is still written.
"$expect" 4 "$o" 'nope.png' -- rk-calibrate lens --images "$W/nope.png" "${board[@]}" -o "$o" --report "$r"
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); assert r["status"] == "failed" and r["exit_code"] == 4, r' "$r"
printf 'not an image\n' > "$W/bad.png"
"$expect" 3 "$o" 'bad.png' -- rk-calibrate lens --images "$W/bad.png" "${board[@]}" -o "$o"
printf 'truncated' > "$W/seq/03.jpg"
"$expect" 3 "$o" '03.jpg' -- rk-calibrate lens --images "$W/seq/%02d.jpg" "${board[@]}" -o "$o"
# Bad options -> 2.
"$expect" 2 "$o" 'board' -- rk-calibrate lens --images "$W/seq/%02d.jpg" --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0.006 -o "$o"
"$expect" 2 "$o" -- rk-calibrate lens --images "$W/seq/%02d.jpg" --board square "${board[@]:2}" -o "$o"
"$expect" 2 "$o" 'cols' -- rk-calibrate lens --images "$W/seq/%02d.jpg" --board chessboard --cols 1 --rows 6 --square-mm 25 --pixel-size-mm 0.006 -o "$o"
"$expect" 2 "$o" 'pixel-size-mm' -- rk-calibrate lens --images "$W/seq/%02d.jpg" --board chessboard --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0 -o "$o"
"$expect" 2 "$o" 'marker-mm' -- rk-calibrate lens --images "$W/seq/%02d.jpg" --board charuco --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0.006 -o "$o"
"$expect" 2 "$o" -- rk-calibrate lens --images "$W/seq/%02d.jpg" "${board[@]}" --reject-ratio 0.5 -o "$o"
"$expect" 2 - -- rk-calibrate lens --images "$W/seq/01.jpg" "${board[@]}" -o "$W/seq/01.jpg"
echo ok
