#!/usr/bin/env bash
# CLI test video_stdin_refused: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/extract; o=$data/extract/stdin_refused.csv
msg='--video -: a video cannot be read from stdin'
# Every tool that takes --video refuses '-' as a usage error (exit 2, one line, no output), with a video on
# stdin or without; also as one of several segments.
"$expect" 2 "$o" "$msg" -- rk-extract beacon --video - --fps 20 -o "$o" < "$d/beacon.mkv"
"$expect" 2 "$o" "$msg" -- rk-extract beacon --video "$d/beacon.mkv" --video - --fps 20 -o "$o" < /dev/null
"$expect" 2 "$o" "$msg" -- rk-extract features --video - --fps 20 --target "$d/none.json" -o "$o" < "$d/beacon.mkv"
"$expect" 2 "$o" "$msg" -- rk-extract silhouette --video - --fps 20 -o "$o" < "$d/beacon.mkv"
"$expect" 2 "$o" "$msg" -- rk-attitude cylinder --points "$d/p.csv" --theodolite "$d/t.csv" --camera "$d/c.json" \
  --target "$d/g.json" --video - -o "$o" < "$d/beacon.mkv"
echo ok
