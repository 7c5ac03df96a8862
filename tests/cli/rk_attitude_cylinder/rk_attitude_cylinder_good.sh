#!/usr/bin/env bash
# CLI test rk_attitude_cylinder_good: registered, and described, in tests/cli/rk_attitude_cylinder.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/att_cyl; mkdir -p "$W"
rm -f "$W/axis.csv" "$W/rep.json"
out=$(rk-attitude cylinder --points "$T/points.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
      --target "$T/target.json" -o "$W/axis.csv" --report "$W/rep.json" --quiet)
test -z "$out"
head -n 1 "$W/axis.csv" | grep -q '^frame,t_s,yaw_deg,pitch_deg,status,alt_yaw_deg,alt_pitch_deg,solution,range_nose_m,range_tail1_m,range_tail2_m,sigma_yaw_deg,sigma_pitch_deg'
test "$(grep -c '' "$W/axis.csv")" = 6
test "$(cut -d, -f5 "$W/axis.csv" | sort -u | tr '\n' ' ')" = "ok status "
rk-analyze compare --estimate "$W/axis.csv" --reference "$T/truth/axis.csv" --columns yaw_deg,pitch_deg,alt_yaw_deg,range_nose_m \
  -o "$W/stats.json"
python3 - "$W/stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k, tol in (("yaw_deg", 1e-4), ("pitch_deg", 1e-4), ("alt_yaw_deg", 1e-4), ("range_nose_m", 1e-2)):
    assert c[k]["n"] == 5 and abs(c[k]["max"]) < tol and abs(c[k]["min"]) < tol, (k, c[k])
PY
grep -q '"ambiguous": 1' "$W/rep.json"
grep -q '"continuity": 4' "$W/rep.json"
rk-attitude cylinder --method search --points "$T/points.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" -o "$W/axis_search.csv" --quiet
diff <(cut -d, -f1-4 "$W/axis.csv") <(cut -d, -f1-4 "$W/axis_search.csv")
echo ok
