#!/usr/bin/env bash
# CLI test rk_sim_attitude_small: registered, and described, in tests/cli/rk_sim_attitude.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
cat > "$data/att_cam.json" <<'EOF'
{"width_px": 1000, "height_px": 800, "pixel_size_mm": [0.00345, 0.00345], "focal_length_mm": 100.0,
 "principal_point_px": [499.5, 399.5], "distortion": [-0.02, 0, 0, 0, 0], "mount_deg": {"yaw": 0.02, "pitch": -0.01, "roll": 0.1}}
EOF
d=$data/att_small
out=$(rk-sim attitude --out "$d" --force --camera "$data/att_cam.json" --range-m 40 --duration 1 --fps 10 \
      --seed 1 --hide fin:0.3:0.3 --report "$data/att_small.json")
test -z "$out"
for f in trial.json target.json turret.csv att/camera.json att/frames.csv att/video.mkv truth/pose.csv truth/points.csv truth/turret.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/truth/pose.csv")" = "frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,range_m,boresight_az_deg,boresight_el_deg"
test "$(head -n 1 "$d/truth/points.csv")" = "frame,t_s,id,x_px,y_px,status,radius_px"
test "$(grep -c '' "$d/truth/pose.csv")" = 11
test "$(grep -c '' "$d/truth/points.csv")" = 81
test "$(grep -c ',fin,,,lost,' "$d/truth/points.csv")" = 3     # t = 1.3, 1.4, 1.5 s
grep -q '"role": "features"' "$d/trial.json"
grep -q '"target": "target.json"' "$d/trial.json"
grep -q '"nose": \[' "$d/target.json"
grep -q '"frames": 10' "$data/att_small.json"
# Initial attitude: yaw 300, pitch 5, roll 0 (the defaults) at frame 0.
grep -q '^0,1.000000000,[^,]*,[^,]*,[^,]*,300.000000000,5.000000000,0.000000000,' "$d/truth/pose.csv"
echo ok
