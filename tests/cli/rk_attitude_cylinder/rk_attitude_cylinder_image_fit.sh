#!/usr/bin/env bash
# CLI test rk_attitude_cylinder_image_fit: registered, and described, in tests/cli/rk_attitude_cylinder.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/att_cyl; mkdir -p "$W"
rm -f "$W/fit.csv" "$W/sil.csv"
rk-extract silhouette --video "$T/theo/%06d.png" --frames "$T/theo/frames.csv" -o "$W/sil.csv" --quiet
rk-attitude cylinder --points "$W/sil.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" --video "$T/theo/%06d.png" -o "$W/fit.csv" --report "$W/fit.json" --quiet
head -n 1 "$W/fit.csv" | grep -q ',fit,fit_rms_dn,fit_psf_px,fit_cone_m,fit_iterations$'
awk -F, 'NR > 1 && $19 == "converged" { n++ } END { exit n != 5 }' "$W/fit.csv"
grep -q '"converged": 5' "$W/fit.json"
rk-analyze compare --estimate "$W/fit.csv" --reference "$T/truth/axis.csv" --columns yaw_deg,pitch_deg -o "$W/fit_stats.json"
python3 - "$W/fit_stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k, tol in (("yaw_deg", 0.25), ("pitch_deg", 0.10)):
    assert c[k]["n"] == 5 and c[k]["max"] < tol and c[k]["min"] > -tol, (k, c[k])
PY
o=$W/fit_bad.csv; rm -f "$o"
args=(--theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" --target "$T/target.json" -o "$o")
cut -d, -f2- "$W/sil.csv" > "$W/sil_noframe.csv"
"$expect" 2 "$o" 'frame. column' -- rk-attitude cylinder --points "$W/sil_noframe.csv" "${args[@]}" --video "$T/theo/%06d.png"
mkdir -p "$W/short"; cp "$T/theo/000000.png" "$T/theo/000001.png" "$W/short/"
"$expect" 3 "$o" 'ends after 2 frames' -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$W/short/%06d.png"
"$expect" 4 "$o" -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$W/none/%06d.png"
"$expect" 2 "$o" -- rk-attitude cylinder --points "$W/sil.csv" "${args[@]}" --video "$T/theo/%06d.png" --fit-psf-sigma 0
echo ok
