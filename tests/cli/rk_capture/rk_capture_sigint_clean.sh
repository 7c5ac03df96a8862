#!/usr/bin/env bash
# CLI test rk_capture_sigint_clean: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_capture/lib.sh"
d=$data/capture_sigint; rm -rf "$d"; mkdir -p "$d"; cd "$d"
rk-sim device dimetix --link "$d/dls" --duration 20 > /dev/null &
dls=$!
trap 'kill $dls 2>/dev/null || true' EXIT
wait_links "$d/dls"
printf '%s\n' '{"width_px": 320, "height_px": 240, "pixel_size_mm": [0.005, 0.005], "focal_length_mm": 25,' \
  '"principal_point_px": [159.5, 119.5]}' > cam.json
cat > station.json <<EOF
{"cameras": [{"name": "att", "source": "synthetic:320x240", "fps": 25, "model": "cam.json",
              "role": "features", "format": "pgm"}],
 "rangefinder": {"port": "dls", "baud": 115200, "mode": "single", "rate_hz": 5}}
EOF
rk-capture --config station.json --out trial --report report.json 2> capture.err &
cap=$!
sleep 2.5
kill -INT $cap
wait $cap
grep -q 'recorded .* s into trial (signal)' capture.err
python3 - <<'PY'
import json
m = json.load(open("trial/trial.json"))
assert m["capture"]["state"] == "complete" and m["capture"]["stop_reason"] == "signal", m["capture"]["state"]
assert m["cameras"]["att"]["video"] == ["att/seg_000/%06d.pgm"], m["cameras"]["att"]
assert m["cameras"]["att"]["model"] == "att/camera.json" and m["cameras"]["att"]["role"] == "features"
assert m["range"] == "range.csv" and m["turret"] is None and m["theodolite"] is None and m["radar"] is None
r = json.load(open("report.json"))
assert r["tool"] == "rk-capture" and r["summary"]["range"]["rows"] >= 8, r["summary"]
PY
cmp cam.json trial/att/camera.json
rk-capture recover trial 2> rec.err
grep -q ' 0 repair(s)' rec.err
echo ok
