# CLI tests of rk-locate (SPEC.md §1.1, §4). The fixture locate_data writes
# tiny inputs to ${RK_CLI_DATA}/locate; every other test here REQUIRES it.
# Scripts are written to the build folder and get $1 = RK_CLI_DATA,
# $2 = expect.sh; rk-locate / rk-analyze are found on PATH (RK_BIN first).
function(rk_locate_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

# Camera: default 50 mm / 3.45 µm; turret at 10 Hz through north; frames at
# 20 Hz; range at 5 Hz with one device-error row (status 7).
rk_locate_script(rk_locate_data [==[
d=$data/locate; rm -rf "$d"; mkdir -p "$d"
cat > "$d/camera.json" <<'EOF'
{"width_px": 2448, "height_px": 2048, "pixel_size_mm": [0.00345, 0.00345],
 "focal_length_mm": 50.0, "principal_point_px": [1223.5, 1023.5],
 "distortion": [-0.05, 0.01, 0.0001, -0.0001, 0], "mount_deg": {"yaw": 0.1, "pitch": -0.05, "roll": 0.2}}
EOF
grep -v focal_length_mm "$d/camera.json" | sed 's/^ "distortion"/ "focal_length_mmX": 1, "distortion"/' > "$d/camera_nofocal.json"
{ echo "# turret log"; echo "t_s,az_deg,el_deg"
  for i in 0 1 2 3 4 5 6 7 8 9 10; do
    awk -v i=$i 'BEGIN { a = 359.8 + 0.04 * i; if (a >= 360) a -= 360; printf "%.3f,%.6f,%.6f\n", 0.1 * i, a, 30 + 0.01 * i }'
  done; } > "$d/turret.csv"
{ echo "frame,t_s,x_px,y_px,peak,area_px,status"
  for k in 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23; do
    awk -v k=$k 'BEGIN { t = 0.02 + 0.05 * k; st = (k == 7) ? "lost" : "ok";
      if (k == 7) printf "%d,%.6f,,,,,%s\n", k, t, st;
      else printf "%d,%.6f,%.4f,%.4f,200,12,%s\n", k, t, 1223.5 + 3 * k, 1023.5 - 2 * k, st }'
  done; } > "$d/track.csv"
printf 't_s,range_m,status\n0.0,80.000,0\n0.2,80.100,0\n0.4,80.200,0\n0.6,,7\n0.8,80.400,0\n1.0,80.500,0\n' > "$d/range.csv"
# Malformed variants.
sed '4s/1229.5000/abc/' "$d/track.csv" > "$d/track_text.csv"
sed '5s/,30\.[0-9]*$/,nan/' "$d/turret.csv" > "$d/turret_nan.csv"
sed '4s/^0.4,/0.1,/' "$d/range.csv" > "$d/range_back.csv"
awk -F, 'NR <= 2 || /^#/ { print; next } { $1 = $1 + 100; printf "%.3f,%s,%s\n", $1, $2, $3 }' OFS=, "$d/turret.csv" > "$d/turret_late.csv"
grep -q abc "$d/track_text.csv"; grep -q nan "$d/turret_nan.csv"; grep -q '^0.1,80.200' "$d/range_back.csv"
grep -q '^100.500' "$d/turret_late.csv"
echo ok
]==] SETUP locate_data)

# Good input: one row per track row, statuses, range statuses, report.
rk_locate_script(rk_locate_good [==[
d=$data/locate; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" \
  -o "$o/located.csv" --report "$o/report.json" --quiet
head -1 "$o/located.csv" | grep -qx 'frame,t_s,az_deg,el_deg,range_m,e_m,n_m,u_m,status,range_status,boresight_az_deg,boresight_el_deg'
test "$(grep -c '' "$o/located.csv")" = 25
grep -q '^7,0.370000000,,,,,,,lost,,' "$o/located.csv"          # lost row kept, empty values
grep -q '^0,0.020000000,359\.[0-9]*,29\.9[0-9]*,80\.010000,' "$o/located.csv"  # az before north, range at 0.02 s
grep -q '^12,0.620000000,0\.[0-9]*,30\.[0-9]*,,,,,ok,device_error,' "$o/located.csv"
grep -q '^20,1.020000000,,,,,,,invalid,,,' "$o/located.csv"      # frames after the turret log (t > 1.0 s)
test "$(grep -c ',invalid,' "$o/located.csv")" = 4
grep -q '"range_coverage"' "$o/report.json"
grep -q '"turret_interp": "cubic"' "$o/report.json"
# Located row 0: the track pixel is the principal point plus distortion/mount:
# compare with the analysis tool against itself (zero error).
rk-analyze compare --estimate "$o/located.csv" --reference "$o/located.csv" --columns az_deg -o "$o/self.json"
grep -q '"rms": 0.0' "$o/self.json"
echo ok
]==] REQUIRES locate_data)

rk_locate_script(rk_locate_stdout [==[
d=$data/locate
rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o - 2>/dev/null > "$d/stdout.csv"
head -1 "$d/stdout.csv" | grep -q '^frame,t_s,az_deg,el_deg,range_m'
grep -q ',ok,none,' "$d/stdout.csv"   # no range log: range_status none
# stdin for the track
cat "$d/track.csv" | rk-locate --track - --camera "$d/camera.json" --turret "$d/turret.csv" -o - -q | cmp - "$d/stdout.csv"
echo ok
]==] REQUIRES locate_data)

rk_locate_script(rk_locate_partial_turret_warns [==[
d=$data/locate
err=$(rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$d/partial.csv" 2>&1 >/dev/null)
echo "$err" | grep -q '^rk-locate: warning: .* not covered by'
echo ok
]==] REQUIRES locate_data)

rk_locate_script(rk_locate_bad_input [==[
d=$data/locate; o=$d/bad.csv; rm -f "$o"
L() { "$expect" "$@"; }
L 3 "$o" 'track_text.csv:4:[0-9]+:' -- rk-locate --track "$d/track_text.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o"
L 3 "$o" 'turret_nan.csv:5:[0-9]+:' -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret_nan.csv" -o "$o"
L 3 "$o" 'range_back.csv:4:[0-9]+:' -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range_back.csv" -o "$o"
L 3 "$o" 'turret_late.csv' -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret_late.csv" -o "$o"
L 3 "$o" 'focal_length_mm' -- rk-locate --track "$d/track.csv" --camera "$d/camera_nofocal.json" --turret "$d/turret.csv" -o "$o"
L 4 "$o" 'no_such.csv' -- rk-locate --track "$d/no_such.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o"
L 4 "$o" -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$d/no_dir/x.csv" -q
L 2 "$o" -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o" --bogus
L 2 "$o" -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" -o "$o"
L 2 "$o" -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o" --range-interp spline
L 2 "$o" -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o" --range-max-gap 0
L 2 - 'refusing to overwrite' -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$d/track.csv"
grep -q '^frame,t_s,x_px' "$d/track.csv"   # input untouched
echo ok
]==] REQUIRES locate_data)

# End to end on rk-sim's small trial: the truth beacon pixels as a perfect
# track. With the true turret the angles must match truth to < 0.05″ RMS
# (limited by the 1e-4 px rounding of truth/beacon.csv); with the logged
# turret (0.003° encoder steps) within 5″ RMS; range RMS ≤ 1 mm (issue target).
rk_locate_script(rk_locate_sim_small [==[
s=$data/small; o=$data/locate_e2e; rm -rf "$o"; mkdir -p "$o"
rk-locate --track "$s/truth/beacon.csv" --camera "$s/az/camera.json" --turret "$s/truth/turret.csv" \
  --range "$s/range.csv" -o "$o/located_true_turret.csv" -q
rk-locate --track "$s/truth/beacon.csv" --camera "$s/az/camera.json" --turret "$s/turret.csv" \
  --range "$s/range.csv" -o "$o/located.csv" -q
rk-analyze compare --estimate "$o/located_true_turret.csv" --reference "$s/truth/target.csv" \
  --columns az_deg,el_deg,range_m --arcsec -o "$o/stats_true_turret.json" -q
rk-analyze compare --estimate "$o/located.csv" --reference "$s/truth/target.csv" \
  --columns az_deg,el_deg,range_m --arcsec -o "$o/stats.json" -q
check() {  # file column key max
  awk -v c="\"$2\"" -v k="\"$3\"" -v m="$4" '
    index($0, c ": {") { inside = 1 }
    inside && index($0, k ":") { v = $0; sub(/.*: /, "", v); sub(/,$/, "", v);
      if (v == "null" || v + 0 > m + 0) { print FILENAME ": " c " " k " = " v " > " m; exit 1 } found = 1; exit 0 }
    END { if (!found) exit 1 }' "$1"
}
check "$o/stats_true_turret.json" az_deg rms 0.05
check "$o/stats_true_turret.json" el_deg rms 0.05
check "$o/stats.json" az_deg rms 5
check "$o/stats.json" el_deg rms 5
check "$o/stats.json" range_m rms 0.001
grep -q ',lost,' "$o/located.csv"   # occluded frames (empty truth pixels) kept as lost rows
echo ok
]==] REQUIRES sim_small)
