# CLI tests of rk-analyze budget (docs/rk-analyze.md): the seed 004 budget shipped in data/seed004, an inline
# locate budget, malformed budgets.
function(rk_ana_bud_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; src=$3\nW=$data/budget; mkdir -p \"$W\"\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT} ${RK_SOURCE_DIR})
endfunction()

# Seed 004 §4.1: the eight angle errors combine to 5.215'; Jacobian and Monte Carlo side by side.
rk_ana_bud_script(rk_analyze_budget_seed004 [==[
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
]==])

rk_ana_bud_script(rk_analyze_budget_locate [==[
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
]==])

rk_ana_bud_script(rk_analyze_budget_bad [==[
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
]==])
