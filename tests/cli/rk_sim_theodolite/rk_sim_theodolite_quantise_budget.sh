#!/usr/bin/env bash
# CLI test rk_sim_theodolite_quantise_budget: registered, and described, in tests/cli/rk_sim_theodolite.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/theo_q; rm -rf "$d"; mkdir -p "$d"
rk-sim theodolite --out "$d/a" --quantise --angle-budget seed004 --seed 4 --duration 0.5 --quiet
rk-sim theodolite --out "$d/b" --quantise --angle-budget seed004 --seed 4 --duration 0.5 --quiet
diff -r -x trial.json "$d/a" "$d/b"
diff <(grep -v '"name"' "$d/a/trial.json") <(grep -v '"name"' "$d/b/trial.json")
awk -F, 'NR > 1 && ($4 != int($4) || $5 != int($5)) { bad = 1 } END { exit bad }' "$d/a/points.csv"
# The recorded angles differ from the true ones by the seed 004 budget (5.1' bias RSS): not zero, < 30'.
paste -d, "$d/a/theodolite.csv" "$d/a/truth/theodolite.csv" | awk -F, 'NR > 1 { e = ($3 - $6) * 60; if (e < 0) e = -e;
  if (e > m) m = e } END { exit !(m > 0.01 && m < 30) }'
echo ok
