#!/usr/bin/env bash
# CLI test rk_extract_silhouette_bad_input: registered, and described, in tests/cli/rk_extract_silhouette.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/ext_sil; mkdir -p "$W"
o=$W/bad.csv; rm -f "$o"
ffmpeg -v error -nostdin -y -f lavfi -i "nullsrc=s=160x120:r=20,format=gray,geq=lum=180" -t 0.2 -pix_fmt gray -c:v ffv1 "$W/sky.mkv"
"$expect" 1 "$o" 'nothing detected' -- rk-extract silhouette --video "$W/sky.mkv" --fps 20 -o "$o"
"$expect" 4 "$o" 'nope' -- rk-extract silhouette --video "$W/nope.mkv" --fps 20 -o "$o"
"$expect" 2 "$o" 'frames' -- rk-extract silhouette --video "$T/theo/%06d.png" -o "$o"
head -n 3 "$T/theo/frames.csv" > "$W/frames_short.csv"
"$expect" 3 "$o" 'frames_short.csv' -- rk-extract silhouette --video "$T/theo/%06d.png" --frames "$W/frames_short.csv" -o "$o"
"$expect" 2 "$o" -- rk-extract silhouette --video "$T/theo/%06d.png" --fps 20 --k-detect 1 -o "$o"
"$expect" 2 - -- rk-extract silhouette --video "$T/theo/%06d.png" --frames "$T/theo/frames.csv" -o "$T/theo/frames.csv"
echo ok
