#!/usr/bin/env bash
# CLI test rk_smooth_resample_bad: registered, and described, in tests/cli/rk_smooth_resample.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/resample; o=$d/bad; rm -rf "$o"; mkdir -p "$o"
r="$d/range.csv"; f="$d/frames.csv"
$expect 3 "$o/x.csv" 'two.csv' -- rk-smooth resample -i "$d/two.csv" --columns range_m --at "$f" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'dup.csv:4:' -- rk-smooth resample -i "$d/dup.csv" --columns range_m --at "$f" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'text.csv:4:' -- rk-smooth resample -i "$d/text.csv" --columns range_m --rate 5 -o "$o/x.csv"
$expect 3 "$o/x.csv" 'range.csv:2:.*range_mm' -- rk-smooth resample -i "$r" --columns range_mm --rate 5 -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_not.csv:1:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_not.csv" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_back.csv:4:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_back.csv" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_text.csv:3:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_text.csv" -o "$o/x.csv"
$expect 4 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$d/none.csv" -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 0 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate -5 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$f" --rate 5 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --method spline -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --max-gap 0 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --margin -1 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$f" --t0 1 -o "$o/x.csv"
$expect 2 - -- rk-smooth resample -i "$r" --columns range_m --at "$f" -o "$f"
echo ok
