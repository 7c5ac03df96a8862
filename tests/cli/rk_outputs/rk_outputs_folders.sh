#!/usr/bin/env bash
# CLI test rk_outputs_folders: registered, and described, in tests/cli/rk_outputs.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
o=$data/outputs/folders; rm -rf "$o"; mkdir -p "$o/disk"
mkdir "$o/disk/trial"; ln -s disk/trial "$o/trial"
rk-sim beacon --out "$o/trial" --preset small --duration 0.5 --format png --seed 3 --quiet
test -L "$o/trial"; test -f "$o/disk/trial/trial.json"
rk-sim beacon --out "$o/trial" --force --preset small --duration 0.5 --format png --seed 4 --quiet
test -L "$o/trial"; test -f "$o/disk/trial/trial.json"
test -z "$(find "$o" "$o/disk" -maxdepth 1 -name '.trial*')"
# rk-run: TRIAL/out is a link to a folder on "another disk"; two runs (the second swaps).
mkdir -p "$o/results/out"; ln -s ../../results/out "$o/disk/trial/out"
rk-run "$o/disk/trial" > /dev/null
test -L "$o/disk/trial/out"; test -f "$o/results/out/report.json"
rk-run --force "$o/disk/trial" > /dev/null
test -L "$o/disk/trial/out"; test -f "$o/results/out/report.json"
test -z "$(find "$o/results" "$o/disk/trial" -maxdepth 1 -name 'out.*')"
# rk-nightly's summary through a link (scripts/rk_output.py).
mkdir "$o/sums"; ln -s sums/nightly.json "$o/summary.json"
python3 "$src/scripts/rk-nightly" "$o/disk" --summary "$o/summary.json" --quiet > /dev/null
test -L "$o/summary.json"; test -s "$o/sums/nightly.json"
echo ok
