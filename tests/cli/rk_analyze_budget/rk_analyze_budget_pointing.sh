#!/usr/bin/env bash
# CLI test rk_analyze_budget_pointing: registered, and described, in tests/cli/rk_analyze_budget.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
W=$data/budget_pointing; rm -rf "$W"; mkdir -p "$W"
cat > "$W/pointing.json" <<'J'
{"az_offset_deg": 0.05, "tilt_north_deg": -0.01, "tilt_east_deg": 0.02, "el_axis_tilt_deg": 0.0,
 "sigma": {"az_offset_deg": 0.005, "tilt_north_deg": 0.001, "tilt_east_deg": 0.001}}
J
cat > "$W/camera.json" <<'J'
{"width_px": 2448, "height_px": 2048, "pixel_size_mm": [0.00345], "focal_length_mm": 50,
 "principal_point_px": [1223.5, 1023.5], "mount_deg": {"yaw": 0.1, "pitch": 0, "roll": 0.2},
 "calibration": {"sigma": {"mount_deg": {"yaw": 0.002, "roll": 0.01}}}}
J
budget() {  # budget FILE [POINTING-LINE]
  cat > "$1" <<J
{"model": "locate", "camera": "camera.json", $2
 "nominal": {"boresight_az_deg": 359.99, "boresight_el_deg": 20, "x_px": 1300, "y_px": 900, "range_m": 800},
 "sources": [{"name": "encoder", "applies_to": "boresight", "sigma_arcsec": 10.8}]}
J
}
budget "$W/with.json" '"pointing": "pointing.json",'
budget "$W/without.json" ''
rk-analyze budget --budget "$W/with.json" --samples 4000 -o "$W/with.out.json"
rk-analyze budget --budget "$W/without.json" --samples 4000 -o "$W/without.out.json"
python3 - "$W/with.out.json" "$W/without.out.json" <<'PY'
import json, math, sys
w, wo = (json.load(open(p)) for p in sys.argv[1:3])
names = [s["name"] for s in w["sources"]]
assert names == ["encoder", "pointing model az_offset", "pointing model tilt_north", "pointing model tilt_east",
                 "camera mount_yaw", "camera mount_roll"], names
assert "pointing.json" in w["sources"][1]["given"], w["sources"][1]
assert [s["name"] for s in wo["sources"]] == ["encoder", "camera mount_yaw", "camera mount_roll"]
inputs = [i["name"] for i in w["model_inputs"]]
for n in ("az_offset", "tilt_north", "tilt_east", "el_axis_tilt", "mount_yaw", "mount_pitch", "mount_roll"):
    assert n in inputs, (n, inputs)
az = {d["name"]: d for d in w["outputs"]}["az"]
az0 = {d["name"]: d for d in wo["outputs"]}["az"]
# The az_offset source adds in quadrature (∂az/∂az_offset = 1 to the tilts' second order); MC agrees.
expect = math.hypot(az0["sigma_jacobian"], 0.005)
assert abs(az["sigma_jacobian"] - expect) < 2e-3 * expect, (az["sigma_jacobian"], expect)
assert abs(az["sigma_monte_carlo"] / az["sigma_jacobian"] - 1) < 0.06, az
# The nominal line of sight turns by the azimuth offset, give or take the tilts' (tilt · tan 20°, < 0.011°).
d = (az["nominal"] - az0["nominal"] + 180) % 360 - 180
assert abs(d - 0.05) < 0.011, d
PY
# Malformed pointing file: its line and column; a cylinder budget with a pointing model.
printf '{"az_offset_deg": 0.05,\n "tilt_north_deg": "x"}\n' > "$W/bad_pointing.json"
budget "$W/bad.json" '"pointing": "bad_pointing.json",'
"$expect" 3 "$W/bad.out.json" 'bad_pointing.json:2:[0-9]+' -- rk-analyze budget --budget "$W/bad.json" -o "$W/bad.out.json"
cat > "$W/cyl.json" <<'J'
{"model": "cylinder", "pointing": "pointing.json",
 "nominal": {"scenario": {"range_m": 300, "az_deg": 10, "el_deg": 5, "yaw_deg": 30, "pitch_deg": 10},
             "target": {"length_m": 2, "diameter_m": 0.3}},
 "sources": [{"name": "encoder", "applies_to": "boresight", "sigma_arcsec": 10.8}]}
J
"$expect" 3 "$W/cyl.out.json" 'cyl.json.*pointing' -- rk-analyze budget --budget "$W/cyl.json" -o "$W/cyl.out.json"
echo ok
