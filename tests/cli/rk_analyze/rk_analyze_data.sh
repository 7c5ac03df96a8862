#!/usr/bin/env bash
# CLI test rk_analyze_data: registered, and described, in tests/cli/rk_analyze.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/analyze; rm -rf "$d"; mkdir -p "$d"
printf '# reference\nt_s,az_deg,range_m\n0,359.9,100\n1,0.1,102\n2,0.3,104\n' > "$d/ref.csv"
printf 't_s,az_deg,range_m,status\n0.5,359.99,101.5,ok\n# a comment\n1.5,0.25,102.9,ok\n2.5,,105,lost\n' > "$d/est.csv"
printf 't_s,az_deg,range_m\n0.5,359.99,abc\n' > "$d/est_text.csv"
printf 't_s,az_deg,range_m\n0.5,nan,1\n' > "$d/est_nan.csv"
printf 't_s,az_deg,range_m\n1,0,100\n0,0,100\n' > "$d/ref_back.csv"
printf 't_s,range_m\n0,1\n1,2\n' > "$d/ref_noaz.csv"
echo ok
