#!/usr/bin/env bash
# CLI test rk_intersect_bad_input: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/intersect; t=$d/trial; o=$d/bad.csv; rm -f "$o"
L() { "$expect" "$@"; }
L 3 "$o" 'stations_syntax.json:2:[0-9]+:' -- rk-intersect --stations "$d/stations_syntax.json" -o "$o"
L 3 "$o" 'stations_nopos.json:[0-9]+:[0-9]+: stations\[2\]\.lat_deg is missing' -- rk-intersect --stations "$d/stations_nopos.json" -o "$o"
L 3 "$o" 'stations_one.json:[0-9]+:[0-9]+: rk-intersect needs at least two stations' -- rk-intersect --stations "$d/stations_one.json" -o "$o"
L 3 "$o" 'stations_late.json: no output time has lines of sight from two stations \(the stations. usable times never overlap: s2 \[10[0-9.]+, 10[0-9.]+\] s, s3 \[0' -- rk-intersect --stations "$d/stations_late.json" -o "$o"
L 3 "$o" 'stations.json: no output time has lines of sight from two stations \(all 2 output times, \[500.000, 501.000\] s, lie outside every station.s rows: s1 ' -- rk-intersect --stations "$t/stations.json" -o "$o" --at "$d/times_after.csv"
L 4 "$o" 'no_such.csv' -- rk-intersect --stations "$d/stations_missing.json" -o "$o"
L 4 "$o" 'no_such.json' -- rk-intersect --stations "$d/no_such.json" -o "$o"
L 4 "$o" -- rk-intersect --stations "$t/stations.json" -o "$d/no_dir/x.csv" -q
L 2 "$o" -- rk-intersect --stations "$t/stations.json" -o "$o" --bogus
L 2 "$o" -- rk-intersect -o "$o"
L 2 "$o" 'exclude' -- rk-intersect --stations "$t/stations.json" -o "$o" --rate 10 --at "$d/times.csv"
L 2 "$o" 'reject-sigma' -- rk-intersect --stations "$t/stations.json" -o "$o" --reject-sigma 0
L 2 - 'refusing to overwrite' -- rk-intersect --stations "$t/stations.json" -o "$t/s1/located.csv"
head -1 "$t/s1/located.csv" | grep -q '^t_s,az_deg'   # input untouched
echo ok
