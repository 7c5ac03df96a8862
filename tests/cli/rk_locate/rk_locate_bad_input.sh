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
# A turret log on another clock (UTC seconds since 1970, frames in trial seconds): both ends readable (fixed
# point: the default notation printed "1.7643e+09 .. 1.7643e+09") and the distance said (issue 27 item 14).
awk -F, '$1 !~ /^[-+0-9.]/ { print; next } { $1 = sprintf("%.6f", $1 + 1764300000) } 1' OFS=, "$d/turret.csv" > "$d/turret_utc.csv"
L 3 "$o" 'turret_utc.csv: turret log covers t_s 17643000[0-9]{2}\.[0-9]{3} \.\. 17643000[0-9]{2}\.[0-9]{3} but .* the log starts [0-9]+\.[0-9]{3} s after the last frame' \
  -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret_utc.csv" -o "$o"
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
