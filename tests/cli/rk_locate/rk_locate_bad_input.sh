#!/usr/bin/env bash
# CLI test rk_locate_bad_input: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
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
