#!/usr/bin/env bash
# CLI test rk_analyze_budget_seed004: registered, and described, in tests/cli/rk_analyze_budget.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
W=$data/budget; mkdir -p "$W"
rk-analyze budget --budget "$src/data/seed004/budget_table2.json" --samples 2000 -o "$W/b.json" --table > "$W/table.txt"
python3 - "$W/b.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
assert b["tool"] == "rk-analyze" and b["model"] == "cylinder"
az = b["model_inputs"][0]
assert az["name"] == "boresight_az" and abs(az["sigma_arcmin"] - 5.215) < 0.0005, az
yaw = b["outputs"][0]
assert yaw["name"] == "yaw" and yaw["unit"] == "deg"
assert yaw["sigma_jacobian"] > 0 and yaw["sigma_monte_carlo"] > 0
assert abs(yaw["sigma_jacobian_by_source"]["crosshair"] - 0.0959) < 0.002, yaw["sigma_jacobian_by_source"]
assert b["jacobian_check"]["max_relative_difference_to_central_differences"] < 1e-4
assert b["monte_carlo"]["samples"] == 2000
PY
grep -q 'sigma_jac' "$W/table.txt"
grep -q '5.2151 arcmin' "$W/table.txt"
echo ok
