#!/usr/bin/env bash
# CLI test rk_attitude_oi_bad: registered, and described, in tests/cli/rk_attitude_oi.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_small
o=$data/att_bad_pose.csv; rm -f "$o"
P="--camera $d/att/camera.json --target $d/target.json"
sed 's/,nose,/,nose2,/' "$d/truth/points.csv" > "$data/att_badid.csv"
"$expect" 3 "$o" "att_badid.csv:[0-9]+:[0-9]+: .*id 'nose2' is not in the target model" -- rk-attitude oi --points "$data/att_badid.csv" $P --turret "$d/turret.csv" -o "$o"
awk -F, 'NR == 1 || $3 == "nose" || $3 == "tail" || $3 == "lwing"' "$d/truth/points.csv" > "$data/att_three.csv"
"$expect" 1 "$o" 'no pose in any of the 10 frames' -- rk-attitude oi --points "$data/att_three.csv" $P --turret "$d/turret.csv" -o "$o"
sed '2s/,belly,[0-9.]*,/,belly,5000.5,/' "$d/truth/points.csv" > "$data/att_outside.csv"
"$expect" 3 "$o" 'att_outside.csv:2:[0-9]+: .*outside the 1000x800 image' -- rk-attitude oi --points "$data/att_outside.csv" $P --turret "$d/turret.csv" -o "$o"
sed '3s/,canopy,/,belly,/' "$d/truth/points.csv" > "$data/att_dup.csv"
"$expect" 3 "$o" 'att_dup.csv:3:[0-9]+: .*twice' -- rk-attitude oi --points "$data/att_dup.csv" $P --turret "$d/turret.csv" -o "$o"
printf '{"points": {"a": [0,0,0], "b": [0.1,0,0], "c": [0.2,0,0], "d": [0.3,0,0]}}' > "$data/att_line2.json"
"$expect" 3 "$o" 'collinear' -- rk-attitude oi --points "$d/truth/points.csv" --camera "$d/att/camera.json" --target "$data/att_line2.json" --turret "$d/turret.csv" -o "$o"
"$expect" 2 "$o" 'turret' -- rk-attitude oi --points "$d/truth/points.csv" $P -o "$o"
"$expect" 2 "$o" -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" --boresight 30,3 -o "$o"
"$expect" 2 "$o" 'elevation' -- rk-attitude oi --points "$d/truth/points.csv" $P --boresight 30,95 -o "$o"
"$expect" 2 "$o" 'AZ,EL' -- rk-attitude oi --points "$d/truth/points.csv" $P --boresight 30 -o "$o"
"$expect" 2 "$o" 'min-points' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" --min-points 3 -o "$o"
printf 't_s,az_deg,el_deg\n500,30,3\n500.02,30,3\n' > "$data/att_turret_late.csv"
"$expect" 3 "$o" 'att_turret_late.csv.*no frame time' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$data/att_turret_late.csv" -o "$o"
"$expect" 2 - 'input' -- rk-attitude oi --points "$d/truth/points.csv" $P --turret "$d/turret.csv" -o "$d/turret.csv"
"$expect" 4 "$o" -- rk-attitude oi --points "$data/no_such_points.csv" $P --turret "$d/turret.csv" -o "$o"
printf 'frame,t_s,id,x_px,y_px\n0,1.0,nose,500,400\n1,0.9,nose,500,400\n' > "$data/att_back.csv"
"$expect" 3 "$o" 'att_back.csv:3:' -- rk-attitude oi --points "$data/att_back.csv" $P --turret "$d/turret.csv" -o "$o"
echo ok
