#!/usr/bin/env bash
# CLI test rk_locate_pointing_bad_input: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$data/locate_pointing_bad; rm -rf "$o"; mkdir -p "$o"
out=$o/out.csv
L() { "$expect" "$@"; }
base=(--track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv")
echo '{"az_offset_deg": "x"}' > "$o/bad_term.json"
echo '{"tilt_east_deg": 12}' > "$o/big_tilt.json"
printf '{"az_offset_deg": 1,\n "sigma": {"az_offset_deg": -1}}\n' > "$o/bad_sigma.json"
echo '{"az_offset_deg": 1,' > "$o/truncated.json"
sed 's/"mount_deg"/"calibration": {"sigma": {"mount_deg": {"yaw": -2}}}, "mount_deg"/' "$d/camera.json" > "$o/camera_bad_sigma.json"
L 4 "$out" 'no_such_pointing.json' -- rk-locate "${base[@]}" --pointing "$o/no_such_pointing.json" -o "$out"
L 3 "$out" 'bad_term.json:1:19: az_offset_deg' -- rk-locate "${base[@]}" --pointing "$o/bad_term.json" -o "$out"
L 3 "$out" 'big_tilt.json:1:19: tilt_east_deg' -- rk-locate "${base[@]}" --pointing "$o/big_tilt.json" -o "$out"
L 3 "$out" 'bad_sigma.json:2:29: sigma.az_offset_deg' -- rk-locate "${base[@]}" --pointing "$o/bad_sigma.json" -o "$out"
L 3 "$out" 'truncated.json:[0-9]+:[0-9]+: ' -- rk-locate "${base[@]}" --pointing "$o/truncated.json" -o "$out"
L 3 "$out" 'camera_bad_sigma.json.*yaw' -- rk-locate --track "$d/track.csv" --camera "$o/camera_bad_sigma.json" \
  --turret "$d/turret.csv" -o "$out"
L 2 "$out" 'station' -- rk-locate "${base[@]}" --station 1,2 -o "$out"
L 2 "$out" 'station' -- rk-locate "${base[@]}" --station 95,0,0 -o "$out"
L 2 "$out" 'station' -- rk-locate "${base[@]}" --station a,b,c -o "$out"
L 2 "$out" 'sigma-px' -- rk-locate "${base[@]}" --sigma-px -1 -o "$out"
L 2 "$out" 'encoder-step-deg' -- rk-locate "${base[@]}" --encoder-step-deg 5 -o "$out"
# rk-attitude takes the same file.
L 4 "$out" 'no_such_pointing.json' -- rk-attitude cylinder --points "$d/track.csv" --theodolite "$d/turret.csv" \
  --camera "$d/camera.json" --target "$d/camera.json" --pointing "$o/no_such_pointing.json" -o "$out"
L 3 "$out" 'bad_term.json:1:19: az_offset_deg' -- rk-attitude cylinder --points "$d/track.csv" --theodolite "$d/turret.csv" \
  --camera "$d/camera.json" --target "$d/camera.json" --pointing "$o/bad_term.json" -o "$out"
L 3 "$out" 'big_tilt.json:1:19: tilt_east_deg' -- rk-attitude cylinder --points "$d/track.csv" --theodolite "$d/turret.csv" \
  --camera "$d/camera.json" --target "$d/camera.json" --pointing "$o/big_tilt.json" -o "$out"
echo ok
