#!/usr/bin/env bash
# CLI test rk_smooth_aukf_bad: registered, and described, in tests/cli/rk_smooth_aukf.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/aukf; o=$d/bad; rm -rf "$o"; mkdir -p "$o"
$expect 3 "$o/x.csv" 'two.csv.*at least 3'       -- rk-smooth aukf -i "$d/two.csv" --columns yaw_deg -o "$o/x.csv"
$expect 3 "$o/x.csv" 'dup.csv:4:[0-9]+: .*repeats' -- rk-smooth aukf -i "$d/dup.csv" --columns yaw_deg -o "$o/x.csv"
$expect 3 "$o/x.csv" 'back.csv:4:[0-9]+: .*backwards' -- rk-smooth aukf -i "$d/back.csv" --columns yaw_deg -o "$o/x.csv"
$expect 3 "$o/x.csv" 'text.csv:4:[0-9]+:'        -- rk-smooth aukf -i "$d/text.csv" --columns yaw_deg -o "$o/x.csv"
$expect 3 "$o/x.csv" 'pitch_deg'                  -- rk-smooth aukf -i "$d/in.csv" --columns pitch_deg -o "$o/x.csv"
$expect 2 "$o/x.csv" 'columns'                    -- rk-smooth aukf -i "$d/in.csv" --columns '' -o "$o/x.csv"
$expect 2 "$o/x.csv" '1 to 12'                    -- rk-smooth aukf -i "$d/in.csv" --columns a,b,c,d,e,f,g,h,i,j,k,l,m -o "$o/x.csv"
$expect 2 "$o/x.csv" 'lead'                       -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --lead 1 -o "$o/x.csv"
$expect 2 "$o/x.csv" 'lead'                       -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --lead 0 -o "$o/x.csv"
$expect 2 "$o/x.csv" 'meas-sigma'                 -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --meas-sigma 1,2 -o "$o/x.csv"
$expect 2 "$o/x.csv" 'adapt'                      -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --adapt both -o "$o/x.csv"
$expect 2 "$o/x.csv" 'fading'                     -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --fading 1.5 -o "$o/x.csv"
$expect 2 "$o/x.csv" 'noise-estimate'             -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --noise-estimate mad -o "$o/x.csv"
$expect 2 "$o/x.csv" 'noise-fit'                  -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --noise-fit online -o "$o/x.csv"
$expect 2 "$o/x.csv" 'smooth-noise-fit'           -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --smooth-noise-fit all -o "$o/x.csv"
$expect 4 "$o/x.csv" 'nothere.csv'                -- rk-smooth aukf -i "$d/nothere.csv" --columns yaw_deg -o "$o/x.csv"
$expect 4 - ''                                    -- rk-smooth aukf -i "$d/in.csv" --columns yaw_deg -o "$o/nodir/x.csv"
cp "$d/in.csv" "$o/same.csv"
$expect 2 - 'input'                               -- rk-smooth aukf -i "$o/same.csv" --columns yaw_deg -o "$o/same.csv"
