#!/usr/bin/env bash
# CLI test rk_extract_points_fps_stdout: registered, and described, in tests/cli/rk_extract_points.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/points_small
fps=$(python3 -c "import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); print(1/(float(r[1]['t_s'])-float(r[0]['t_s'])))" "$d/frames.csv")
rk-extract points --video "$d/video.mkv" --fps "$fps" --seeds "$d/seeds.csv" -o - --quiet > "$data/points_stdout.csv"
# The same positions and statuses (times may differ in the last digit of the rate).
cut -d, -f1,3-6 "$d/points.csv" > "$data/points_a.txt"
cut -d, -f1,3-6 "$data/points_stdout.csv" > "$data/points_b.txt"
cmp "$data/points_a.txt" "$data/points_b.txt"
echo ok
