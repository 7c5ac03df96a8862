#!/usr/bin/env bash
# CLI test rk_analyze_budget_locate: registered, and described, in tests/cli/rk_analyze_budget.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
W=$data/budget; mkdir -p "$W"
cat > "$W/loc.json" <<'J'
{"model": "locate", "nominal": {"boresight_az_deg": 359.99, "boresight_el_deg": 20, "x_px": 1300, "y_px": 900, "range_m": 80},
 "sources": [{"name": "encoder", "applies_to": "boresight", "sigma_arcsec": 10.8},
             {"name": "centroid", "applies_to": "pixels", "sigma_px": 0.03},
             {"name": "range", "applies_to": "range", "sigma_mm": 2}]}
J
rk-analyze budget --budget "$W/loc.json" --samples 5000 -o - | python3 -c '
import json, sys
b = json.load(sys.stdin)
for o in b["outputs"]:
    r = o["sigma_monte_carlo"] / o["sigma_jacobian"]
    assert 0.95 < r < 1.05, (o["name"], r)
'
echo ok
