#!/usr/bin/env bash
# CLI test rk_calibrate_lens_good: registered, and described, in tests/cli/rk_calibrate_lens.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
D=/usr/share/doc/opencv-doc/examples/data
W=$data/cal_lens; mkdir -p "$W"
rm -f "$W/camera.json" "$W/plot.png" "$W/rep.json"
rk-calibrate lens --images "$D/left0%d.jpg" --images "$D/left1%d.jpg" --board chessboard --cols 9 --rows 6 --square-mm 25 \
  --pixel-size-mm 0.006 --fix-aspect -o "$W/camera.json" --plot "$W/plot.png" --report "$W/rep.json" --quiet
python3 - "$W/camera.json" "$W/rep.json" <<'PY'
import json, sys
cam = json.load(open(sys.argv[1])); rep = json.load(open(sys.argv[2]))
for k in ("width_px", "height_px", "pixel_size_mm", "focal_length_mm", "principal_point_px", "distortion"):
    assert k in cam, k
assert (cam["width_px"], cam["height_px"]) == (640, 480)
fx = cam["focal_length_mm"] / cam["pixel_size_mm"][0]
assert abs(fx - 535.9) < 6, fx  # OpenCV's left_intrinsics.yml: 535.92
assert cam["pixel_size_mm"][0] == cam["pixel_size_mm"][1]  # --fix-aspect
c = cam["calibration"]
for k in ("method", "date", "rms_px", "views_used", "views_rejected", "sigma"):
    assert k in c, k
assert len(c["views_used"]) + len(c["views_rejected"]) == 13
assert all(r["reason"] for r in c["views_rejected"])
assert c["sigma"]["fx_px"] > 0 and len(c["sigma"]["distortion"]) == 5
# The predicted map error: positive, and the part a rotation cannot absorb no larger than the whole.
assert 0 < c["map_sigma_modulo_rotation_px"] <= c["map_sigma_px"], c
s = rep["summary"]
assert rep["status"] == "ok" and s["views"] == 13 and s["views_used"] == len(c["views_used"]), s
assert abs(s["rms_px"] - c["rms_px"]) < 1e-12 and s["map_sigma_px"] == c["map_sigma_px"]
print("fx %.2f rms %.3f used %d" % (fx, c["rms_px"], s["views_used"]))
PY
test "$(head -c 8 "$W/plot.png" | od -An -c | tr -d ' ')" = '211PNG\r\n032\n'
# Single image files given one by one, and -o - (stdout carries only the JSON).
rk-calibrate lens --images "$D/left01.jpg" --images "$D/left02.jpg" --images "$D/left03.jpg" --images "$D/left04.jpg" \
  --board chessboard --cols 9 --rows 6 --square-mm 25 --pixel-size-mm 0.006 --fix-k3 -o - --quiet |
  python3 -c 'import json, sys; c = json.load(sys.stdin)["calibration"]; assert len(c["views_used"]) + len(c["views_rejected"]) == 4; assert c["sigma"]["distortion"][4] is None'
echo ok
