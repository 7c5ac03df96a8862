#!/usr/bin/env bash
# CLI test rk_smooth_resample_good: registered, and described, in tests/cli/rk_smooth_resample.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/resample; o=$d/out; rm -rf "$o"; mkdir -p "$o"
for m in linear cubic kalman; do
  rk-smooth resample -i "$d/range.csv" --columns range_m --at "$d/frames.csv" --method $m -o "$o/$m.csv" \
    --report "$o/$m.json" --quiet
  head -1 "$o/$m.csv" | grep -qx 't_s,frame,kind,range_m,status,reason'
  test "$(grep -c '' "$o/$m.csv")" = 122
  grep -q '^0.000000000,0,[a-z]*,,invalid,outside$' "$o/$m.csv"     # before the log
  grep -q '^0.050000000,1,[a-z]*,,invalid,outside$' "$o/$m.csv"
  grep -q '^6.000000000,120,[a-z]*,,invalid,outside$' "$o/$m.csv"   # after the log
  grep -q '^3.500000000,70,[a-z]*,,lost,gap$' "$o/$m.csv"           # in the hole
  test "$(grep -c ',lost,gap$' "$o/$m.csv")" = 23                   # 2.9 < t < 4.1
  # Device-error row at 1.1 s is bridged; values on the line 40 + 2 t.
  awk -F, -v m=$m '$5 == "ok" { e = $4 - (40 + 2 * $1); if (e < 0) e = -e; if (e > (m == "kalman" ? 1e-4 : 1e-6)) exit 1; n++ }
    END { exit !(n == 94) }' "$o/$m.csv"
  grep -q '"rows_gap": 23' "$o/$m.json"
  grep -q '"rows_masked_by_status": 0' "$o/$m.json"
done
grep -q '^0.100000000,2,smoothed,40.2' "$o/kalman.csv"
grep -q '^0.100000000,2,estimate,40.2' "$o/linear.csv"
grep -q '"max_gap_s": 0.5' "$o/kalman.json"
# --margin lets the ends be extrapolated; --rate with --t0/--t1; --sigmas; stdout.
rk-smooth resample -i "$d/range.csv" --columns range_m --at "$d/frames.csv" --margin 0.06 -o "$o/margin.csv"
awk -F, '$1 == "0.050000000" { if ($4 < 40.099 || $4 > 40.101 || $5 != "ok") exit 1; f = 1 } END { exit !f }' "$o/margin.csv"
grep -q '^0.000000000,0,smoothed,,invalid,outside$' "$o/margin.csv"
rk-smooth resample -i "$d/range.csv" --columns range_m --rate 10 --t0 1 --t1 2 --sigmas -o - > "$o/rate.csv"
head -1 "$o/rate.csv" | grep -qx 't_s,kind,range_m,status,reason,range_sigma_m'
test "$(grep -c '' "$o/rate.csv")" = 12
awk -F, '$1 == "1.500000000" { if ($2 != "smoothed" || $3 < 42.999 || $3 > 43.001 || $4 != "ok" || $6 <= 0) exit 1; f = 1 } END { exit !f }' "$o/rate.csv"
rk-smooth resample -i "$d/range.csv" --columns range_m --rate 5 --method linear --max-gap 2 -o "$o/rate5.csv"
test "$(grep -c ',ok,' "$o/rate5.csv")" = 30                        # 0.1 .. 5.9 s, hole bridged
echo ok
