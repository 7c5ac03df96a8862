#!/usr/bin/env bash
# CLI test import_cli_tools_take_file_times: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
i=$data/import
x=$data/extract
# The beacon as a Photron file at 20 fps, without --frames/--fps: the same rows as the MKV with --fps 20.
rk-extract beacon --video "$i/beacon.mraw" -o "$i/track_mraw.csv" 2> "$i/track_mraw.err"
cat "$i/track_mraw.err"
grep -q "frame times of .*beacon.mraw: no per-frame stamps in a Photron file" "$i/track_mraw.err"
rk-extract beacon --video "$x/beacon.mkv" --fps 20 -o "$i/track_mkv.csv"
cmp "$i/track_mraw.csv" "$i/track_mkv.csv"
# A recording whose time goes back: the tools stop with the frame named (their rows must be in time order).
"$expect" 3 "$i/track_gaps.csv" "gaps.cine: frame 4: time goes back by 0.001000000 s" -- \
  rk-extract beacon --video "$i/gaps.cine" -o "$i/track_gaps.csv" --quiet
# rk-calibrate lens --images: OpenCV's board views as grey PNGs and as one 8-bit MRAW give the same calibration.
b=$i/board
mkdir -p "$b"
n=0
for f in /usr/share/doc/opencv-doc/examples/data/left0{1,2,3,4,5,6,7,8,9}.jpg /usr/share/doc/opencv-doc/examples/data/left1{1,2,3,4}.jpg; do
  ffmpeg -v error -nostdin -y -i "$f" -pix_fmt gray "$(printf "$b/%06d.png" $n)"
  n=$((n + 1))
done
ffmpeg -v error -nostdin -y -i "$b/%06d.png" -f rawvideo -pix_fmt gray "$b/views.mraw"
/usr/bin/python3 - "$b/views.cihx" "$n" "$src" <<'PY'
import os, sys
sys.path.insert(0, os.path.join(sys.argv[3], "tests", "fuzz"))
import make_camera_seeds as seeds
open(sys.argv[1], "wb").write(seeds.cihx(640, 480, 8, int(sys.argv[2])))
PY
args="--board chessboard --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0.006"
rk-calibrate lens --images "$b/%06d.png" $args -o "$b/cam_png.json" --quiet
rk-calibrate lens --images "$b/views.mraw" $args -o "$b/cam_mraw.json" --quiet
/usr/bin/python3 - "$b/cam_png.json" "$b/cam_mraw.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
# Everything equal but the date and the names of the views (file names against frames of the .mraw).
for cam in (a, b):
    del cam["calibration"]["date"]
    assert len(cam["calibration"].pop("views_used")) == 13
assert a == b, (a, b)
PY
echo PASS
