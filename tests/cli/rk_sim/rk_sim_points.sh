#!/usr/bin/env bash
# CLI test rk_sim_points: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/sim_points; rm -rf "$d" "$d.json"
out=$(rk-sim points --out "$d" --scenario lookalike --frames 6 --seed 3 --exposure 0 \
      --reseed q2:4 --report "$d.json" --quiet)
test -z "$out"
for f in video.mkv frames.csv seeds.csv truth/points.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/frames.csv")" = "frame,t_s"
test "$(head -n 1 "$d/seeds.csv")" = "id,frame,x_px,y_px,method,size_px"
test "$(head -n 1 "$d/truth/points.csv")" = "frame,t_s,id,x_px,y_px,visible,occlusion"
test "$(grep -c '' "$d/frames.csv")" = 7
# Seven markers seeded at frame 0, and q2 again at its truth at frame 4 (the same numbers as the truth row).
test "$(grep -c ',0,' "$d/seeds.csv")" = 7
q2seed=$(grep '^q2,4,' "$d/seeds.csv" | cut -d, -f3,4)
q2truth=$(grep '^4,[^,]*,q2,' "$d/truth/points.csv" | cut -d, -f4,5)
test -n "$q2seed" && test "$q2seed" = "$q2truth" || { echo "re-seed $q2seed vs truth $q2truth"; exit 1; }
# 8 ids per frame (7 markers and the look-alike), x and y with 6 decimals.
test "$(grep -c '' "$d/truth/points.csv")" = 49
grep -Eq '^0,[0-9.]+,q1,[0-9]+\.[0-9]{6},[0-9]+\.[0-9]{6},1,' "$d/truth/points.csv"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); sys.exit(r['summary']['frames'] != 6 or r['options']['scenario'] != 'lookalike')" "$d.json"
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=width,height,nb_read_frames \
    -of csv=p=0 "$d/video.mkv")
test "$n" = "640,480,6" || { echo "video: $n"; exit 1; }
echo ok
