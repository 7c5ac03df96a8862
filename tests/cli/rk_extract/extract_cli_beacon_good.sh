#!/usr/bin/env bash
# CLI test extract_cli_beacon_good: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract; h=$src/tests/cli/rk_extract
rm -f "$x/track.csv" "$x/report.json"
rk-extract beacon --video "$x/beacon.mkv" --frames "$x/frames.csv" -o "$x/track.csv" --report "$x/report.json" --quiet
sh "$h/check_track.sh" "$x/track.csv" 60 100 0.02
grep -q '"ok": 60' "$x/report.json"
grep -q '"mean_ncc"' "$x/report.json"
