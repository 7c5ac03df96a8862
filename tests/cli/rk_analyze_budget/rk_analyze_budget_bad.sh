#!/usr/bin/env bash
# CLI test rk_analyze_budget_bad: registered, and described, in tests/cli/rk_analyze_budget.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
W=$data/budget; mkdir -p "$W"
o=$W/bad.json; rm -f "$o"
echo '{"model": "radar", "nominal": {}, "sources": []}' > "$W/m.json"
"$expect" 3 "$o" "unknown model 'radar'" -- rk-analyze budget --budget "$W/m.json" -o "$o"
sed 's/"sigma_arcmin": 5}/"sigma_px": 5}/' "$src/data/seed004/budget_table2.json" > "$W/u.json"
"$expect" 3 "$o" 'u.json.*cannot apply' -- rk-analyze budget --budget "$W/u.json" -o "$o"
printf '{"model": "cylinder",\n "nominal": [1,\n' > "$W/syntax.json"
"$expect" 3 "$o" 'syntax.json:3' -- rk-analyze budget --budget "$W/syntax.json" -o "$o"
"$expect" 4 "$o" 'nope.json' -- rk-analyze budget --budget "$W/nope.json" -o "$o"
"$expect" 2 "$o" 'samples' -- rk-analyze budget --budget "$src/data/seed004/budget_table2.json" --samples -1 -o "$o"
"$expect" 2 - -- rk-analyze budget --budget "$W/m.json" -o "$W/m.json"
echo ok
