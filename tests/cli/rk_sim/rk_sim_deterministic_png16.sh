#!/usr/bin/env bash
# CLI test rk_sim_deterministic_png16: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/sim_det; rm -rf "$d"; mkdir -p "$d"
for x in a b; do
  rk-sim beacon --out "$d/$x" --preset small --duration 0.5 --format png --bit-depth 16 --seed 7 \
    --distractors 2 --report "$d/$x.json"
done
test -s "$d/a/az/000009.png"
test ! -e "$d/a/az/000010.png"
diff -r -x trial.json "$d/a" "$d/b"
grep -q '"visible_frames": 10' "$d/a.json"
rk-sim beacon --out "$d/c" --preset small --duration 0.5 --format png --bit-depth 16 --seed 8 --distractors 2
if cmp -s "$d/a/az/000000.png" "$d/c/az/000000.png"; then echo "seed has no effect"; exit 1; fi
echo ok
