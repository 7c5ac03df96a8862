#!/usr/bin/env bash
# CLI test rk_attitude_oi_good: registered, and described, in tests/cli/rk_attitude_oi.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
o=$data/att_pose.csv; rm -f "$o"
out=$(rk-attitude oi --points "$data/att_points.csv" --camera "$d/att/camera.json" --target "$d/target.json" \
      --turret "$d/turret.csv" -o "$o" --report "$data/att_pose.json")
test -z "$out"
head -n 1 "$o" | grep -q '^frame,t_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status,reproj_rms_px,'
test "$(grep -c '' "$o")" = 11
test "$(cut -d, -f9 "$o" | sort | uniq -c | awk '{print $1 $2}' | tr '\n' ' ')" = "10ok 1status "
rk-analyze compare --estimate "$o" --reference "$d/truth/pose.csv" --columns yaw_deg,pitch_deg,roll_deg,e_m,n_m,u_m \
  -o "$data/att_pose_stats.json"
python3 - "$data/att_pose_stats.json" <<'EOF'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
for k in ("yaw_deg", "pitch_deg", "roll_deg"):
    assert abs(c[k]["max"]) < 0.05 and abs(c[k]["min"]) < 0.05, (k, c[k])
for k in ("e_m", "n_m", "u_m"):
    assert abs(c[k]["max"]) < 0.02 and abs(c[k]["min"]) < 0.02, (k, c[k])
print("ok", {k: c[k]["std"] for k in c})
EOF
grep -q '"ok": 10' "$data/att_pose.json"
grep -q '"mean_chi2_per_dof"' "$data/att_pose.json"
# Frames with the fin hidden used 7 points.
test "$(awk -F, 'NR > 1 && $12 == 7' "$o" | grep -c '')" = 3
echo ok
