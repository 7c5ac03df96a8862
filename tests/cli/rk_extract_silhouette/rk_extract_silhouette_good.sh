#!/usr/bin/env bash
# CLI test rk_extract_silhouette_good: registered, and described, in tests/cli/rk_extract_silhouette.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/theo_trial
W=$data/ext_sil; mkdir -p "$W"
rm -f "$W/points.csv" "$W/rep.json"
rk-extract silhouette --video "$T/theo/%06d.png" --frames "$T/theo/frames.csv" -o "$W/points.csv" --report "$W/rep.json" --quiet
test "$(head -n 1 "$W/points.csv")" = "frame,t_s,id,x_px,y_px,status,detail,width_px,length_px"
test "$(grep -c '' "$W/points.csv")" = 16
grep -q '"ok": 5' "$W/rep.json"
awk -F, 'NR == FNR { if (FNR > 1) { x[$1 "," $3] = $4; y[$1 "," $3] = $5 }; next }
         FNR > 1 { k = $1 "," $3; d = ($4 - x[k])^2 + ($5 - y[k])^2; s += d; n++; if ($6 != "ok") bad++ }
         END { rms = sqrt(s / n); printf "points %d, not ok %d, rms %.4f px\n", n, bad, rms; exit !(n == 15 && bad == 0 && rms < 0.3) }' \
  "$T/truth/points.csv" "$W/points.csv"
rk-attitude cylinder --points "$W/points.csv" --theodolite "$T/theodolite.csv" --camera "$T/theo/camera.json" \
  --target "$T/target.json" -o "$W/axis.csv" --quiet
awk -F, 'NR > 1 && $5 == "ok" { n++ } END { exit n != 5 }' "$W/axis.csv"
# --fps and two segments (frame numbers count on).
rk-extract silhouette --video "$T/theo/%06d.png" --video "$T/theo/%06d.png" --fps 20 --t0 1 -o - --quiet |
  awk -F, 'NR > 1 { n++; f = $1 } END { exit !(n == 30 && f == 9) }'
echo ok
