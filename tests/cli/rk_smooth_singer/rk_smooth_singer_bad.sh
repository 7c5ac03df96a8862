#!/usr/bin/env bash
# CLI test rk_smooth_singer_bad: registered, and described, in tests/cli/rk_smooth_singer.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/singer; o=$d/bad; rm -rf "$o"; mkdir -p "$o"
$expect 3 "$o/x.csv" 'two.csv' -- rk-smooth singer -i "$d/two.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'dup.csv:4:' -- rk-smooth singer -i "$d/dup.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'back.csv:4:' -- rk-smooth singer -i "$d/back.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'text.csv:4:' -- rk-smooth singer -i "$d/text.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'sparse.csv' -- rk-smooth singer -i "$d/sparse.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'badstatus.csv:4:' -- rk-smooth singer -i "$d/badstatus.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'range.csv:1:.*speed_m' -- rk-smooth singer -i "$d/range.csv" --columns speed_m -o "$o/x.csv"
$expect 4 "$o/x.csv" -- rk-smooth singer -i "$d/nonexistent.csv" --columns range_m -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --maneuver-time 0
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --meas-sigma -1
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --accel-sigma 1,2
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --accel-sigma abc
$expect 2 "$o/x.csv" 'accel-sigma' -- rk-smooth singer -i "$d/range.csv" --columns status -o "$o/x.csv"  # no unit
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" -o "$o/x.csv"
$expect 2 - -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$d/range.csv"
echo ok
