#!/usr/bin/env bash
# CLI test rk_sim_attitude_wraps_and_determinism: registered, and described, in tests/cli/rk_sim_attitude.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/att_wrap; rm -rf "$d"; mkdir -p "$d"
rk-sim attitude --out "$d/a" --name w --no-video --fps 2 --yaw0-deg 355 --roll0-deg 177 --path-angle-deg 0 --quiet
rk-sim attitude --out "$d/b" --name w --no-video --fps 2 --yaw0-deg 355 --roll0-deg 177 --path-angle-deg 0 --quiet
diff -r "$d/a" "$d/b" >/dev/null || { echo "not deterministic"; exit 1; }
awk -F, 'NR > 1 { if ($6 < 0 || $6 >= 360 || $8 <= -180 || $8 > 180) bad = 1;
                  if ($6 < 5) ylo = 1; if ($6 > 355) yhi = 1; if ($8 > 177) rp = 1; if ($8 < -178) rn = 1 }
         END { exit !(ylo && yhi && rp && rn && !bad) }' "$d/a/truth/pose.csv"
test ! -e "$d/a/att/video.mkv"
# No video, no camera in the manifest (SPEC.md §6 wants a non-empty video list): rk-run has nothing to extract
python3 -c "import json,sys; m = json.load(open(sys.argv[1])); assert m['cameras'] == {}, m['cameras']" "$d/a/trial.json"
echo ok
