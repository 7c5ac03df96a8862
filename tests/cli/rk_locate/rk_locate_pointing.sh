#!/usr/bin/env bash
# CLI test rk_locate_pointing: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$data/locate_pointing; rm -rf "$o"; mkdir -p "$o"
echo '{"az_offset_deg": 0, "tilt_north_deg": 0}' > "$o/zero.json"
cat > "$o/pointing.json" <<'EOF'
{"az_offset_deg": 2.5, "tilt_north_deg": 0.3, "tilt_east_deg": -0.2, "el_axis_tilt_deg": 0.1,
 "sigma": {"az_offset_deg": 0.001, "tilt_north_deg": 0.0003}, "observations": 120}
EOF
base=(--track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv")
rk-locate "${base[@]}" -o "$o/plain.csv" -q
rk-locate "${base[@]}" --pointing "$o/zero.json" -o "$o/zero.csv" -q
rk-locate "${base[@]}" --pointing "$o/pointing.json" --station -33.9,18.4,120 -o "$o/pm.csv" \
  --report "$o/pm.json" -q
# A zero pointing model changes nothing.
cmp "$o/plain.csv" "$o/zero.csv"
# The SPEC.md §2.1 columns: 1σ always, lat/lon/h with --station.
head -1 "$o/plain.csv" | grep -q ',sigma_az_deg,sigma_el_deg,sigma_range_m,sigma_e_m,sigma_n_m,sigma_u_m,corr_az_el$'
head -1 "$o/pm.csv" | grep -q ',sigma_u_m,corr_az_el,lat_deg,lon_deg,h_m$'
# The pointing model moves the azimuth by about the offset (2.5° + the tilts' share) and no row is lost.
paste -d, <(cut -d, -f3 "$o/plain.csv") <(cut -d, -f3 "$o/pm.csv") | awk -F, '
  NR > 1 && $1 != "" { d = $2 - $1; if (d < -180) d += 360; if (d > 180) d -= 360;
    if (d < 2.0 || d > 3.0) { print "az shift " d; bad = 1 } n++ }
  END { exit (bad || n < 15) }'
# σ: the azimuth offset's 0.001° dominates sigma_az (≈ 0.001° at 30° elevation, 3.6″); lat near the station.
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  $c["status"] == "ok" { s = $c["sigma_az_deg"]; if (s < 0.0009 || s > 0.0015) { print "sigma_az " s; bad = 1 }
    if ($c["sigma_e_m"] == "" && $c["range_m"] != "") { print "no sigma_e"; bad = 1 }
    r = $c["corr_az_el"]; if (r == "" || r < -1 || r > 1) { print "corr_az_el " r; bad = 1 }
    if ($c["range_m"] != "" && ($c["lat_deg"] < -33.91 || $c["lat_deg"] > -33.89)) { print "lat " $c["lat_deg"]; bad = 1 } }
  END { exit bad }' "$o/pm.csv"
grep -q '"pointing"' "$o/pm.json"
grep -q '"lat_deg": -33.9' "$o/pm.json"
echo ok
