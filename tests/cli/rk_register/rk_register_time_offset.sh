#!/usr/bin/env bash
# CLI test rk_register_time_offset: registered, and described, in tests/cli/rk_register.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/radar_off; rm -rf "$d"
rk-sim radar --out "$d" --scenario 1 --steps 40 --seed 2 --time-offset-b 0.3 --nav-rate 1
rk-register bernoulli --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$d/b.csv" --report "$d/b.json"
test "$(grep -c '' "$d/b.csv")" = 41
sed -n 2p "$d/b.csv" | grep -q '^0.300000000,'
grep -q '"max_pair_offset_s": 0.3' "$d/b.json"
# A tolerance below the offset pairs nothing: exit 1 with the offset in the message, no output.
"$expect" 1 "$d/b0.csv" "typically 0.3 s after radar 'a'.*raise --pair-tol" -- \
  rk-register bernoulli --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$d/b0.csv" --pair-tol 0.1
echo ok
