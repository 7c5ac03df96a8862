# CLI tests of rk-extract silhouette (SPEC.md §1.1, §4; docs/rk-extract.md) on the rendered frames of the
# fixture sim_theodolite_trial, and malformed input.
function(rk_ext_sil_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\nT=$data/theo_trial\nW=$data/ext_sil; mkdir -p \"$W\"\n${body}")
  rk_cli_test(${name} ${ARGN} REQUIRES sim_theodolite_trial
              COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

# Sub-pixel points within 0.3 px of the exact projections, then the attitude from them.
rk_ext_sil_script(rk_extract_silhouette_good [==[
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
]==])

rk_ext_sil_script(rk_extract_silhouette_bad_input [==[
o=$W/bad.csv; rm -f "$o"
ffmpeg -v error -nostdin -y -f lavfi -i "nullsrc=s=160x120:r=20,format=gray,geq=lum=180" -t 0.2 -pix_fmt gray -c:v ffv1 "$W/sky.mkv"
"$expect" 1 "$o" 'nothing detected' -- rk-extract silhouette --video "$W/sky.mkv" --fps 20 -o "$o"
"$expect" 4 "$o" 'nope' -- rk-extract silhouette --video "$W/nope.mkv" --fps 20 -o "$o"
"$expect" 2 "$o" 'frames' -- rk-extract silhouette --video "$T/theo/%06d.png" -o "$o"
head -n 3 "$T/theo/frames.csv" > "$W/frames_short.csv"
"$expect" 3 "$o" 'frames_short.csv' -- rk-extract silhouette --video "$T/theo/%06d.png" --frames "$W/frames_short.csv" -o "$o"
"$expect" 2 "$o" -- rk-extract silhouette --video "$T/theo/%06d.png" --fps 20 --k-detect 1 -o "$o"
"$expect" 2 - -- rk-extract silhouette --video "$T/theo/%06d.png" --frames "$T/theo/frames.csv" -o "$T/theo/frames.csv"
echo ok
]==])
