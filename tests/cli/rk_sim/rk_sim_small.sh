#!/usr/bin/env bash
# CLI test rk_sim_small: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/small
out=$(rk-sim beacon --out "$d" --force --preset small --duration 3 --format mkv --seed 1 \
      --occlusion 1.5:0.5 --distractors 1 --range-error-rate 0.05 --quiet)
test -z "$out"
for f in trial.json az/camera.json az/frames.csv az/video.mkv turret.csv range.csv \
         truth/beacon.csv truth/target.csv truth/turret.csv truth/range.csv; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(grep -c '' "$d/az/frames.csv")" = 61
test "$(grep -c ',,0,' "$d/truth/beacon.csv")" = 10
grep -q ',,255$' "$d/range.csv"
n=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=width,height,nb_read_frames \
    -of csv=p=0 "$d/az/video.mkv")
test "$n" = "640,512,60" || { echo "video: $n"; exit 1; }
echo "sim_small ok"
