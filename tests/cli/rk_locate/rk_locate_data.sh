#!/usr/bin/env bash
# CLI test rk_locate_data: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
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
