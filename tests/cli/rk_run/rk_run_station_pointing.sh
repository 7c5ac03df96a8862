#!/usr/bin/env bash
# CLI test rk_run_station_pointing: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
t=$data/run/station_pointing; rm -rf "$t"; mkdir -p "$data/run"
rk-sim beacon --out "$t" --preset small --duration 2 --format mkv --seed 5 --quiet \
  --az-offset-deg 2.5 --tilt-north-deg 0.3 --tilt-east-deg -0.2 --el-axis-tilt-deg 0.1 --time-offset-s 0.02
python3 - "$t/trial.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["station"].update({"lat_deg": 34.5, "lon_deg": 108.9, "h_m": 412.0, "pointing": "truth/pointing.json"})
json.dump(m, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots -q
grep -q -- '--pointing truth/pointing.json --station 34.5,108.9,412 ' "$t/out/steps/az.locate.log"
head -1 "$t/out/az/located.csv" | grep -q ',lat_deg,lon_deg,h_m$'
rk-analyze compare --estimate "$t/out/az/located.csv" --reference "$t/truth/target.csv" --columns az_deg,el_deg \
  --arcsec -o "$t/stats.json" -q
python3 - "$t/stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k in ("az_deg", "el_deg"):  # the extractor and the 0.003° encoder, as for a perfect station (5″)
    assert c[k]["n"] > 30 and c[k]["rms"] < 5, (k, c[k])
print("ok", {k: round(c[k]["rms"], 3) for k in c})
PY
# A changed pointing model re-runs locate (it is an input of the step).
echo '{"az_offset_deg": 2.5}' > "$t/truth/pointing.json"
rk-run "$t" --no-plots > "$t/again.out"
grep -q 'az/locate' "$t/again.out"
grep -q 'input changed: truth/pointing.json' "$t/again.out"
echo ok
