#!/usr/bin/env bash
# CLI test extract_cli_sim_sparse_per_lamp: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract; h=$src/tests/cli/rk_extract
d=$x/sparse
rk-sim beacon --out "$d" --force --preset small --duration 2 --seed 6 --cluster-span-m 0.1 --quiet
rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --report "$d/report.json" --quiet
sh "$h/check_sim.sh" "$d/track.csv" "$d/truth/beacon.csv"
grep -q '"per_lamp": 40' "$d/report.json"
grep -q '"cluster": 0' "$d/report.json"
