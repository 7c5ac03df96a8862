#!/usr/bin/env bash
# CLI test rk_smooth_singer_good: registered, and described, in tests/cli/rk_smooth_singer.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/singer; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/motion.csv" --sigmas --report "$o/r.json" --quiet
head -1 "$o/motion.csv" | grep -qx 't_s,kind,range_m,status,range_rate_m_s,range_accel_m_s2,range_sigma_m,range_rate_sigma_m_s,range_accel_sigma_m_s2'
test "$(grep -c '' "$o/motion.csv")" = 41
test "$(grep -c ',smoothed,' "$o/motion.csv")" = 40
test "$(grep -c ',predicted,' "$o/motion.csv")" = 2     # device error + masked 999 row
awk -F, '$1 == "4.000000000" { if ($3 < 55.59 || $3 > 55.61 || $4 != "predicted") exit 1; f = 1 } END { exit !f }' "$o/motion.csv"  # masked row
# Rate at t = 3 s: 1 + 0.2*3 = 1.6 m/s; acceleration 0.2 m/s^2 (noise-free input).
awk -F, '$1 == "3.000000000" { if ($5 < 1.59 || $5 > 1.61 || $6 < 0.17 || $6 > 0.23) exit 1; f = 1 } END { exit !f }' "$o/motion.csv"
grep -q '"rows_masked_by_status": 1' "$o/r.json"
grep -q '"meas_sigma_estimated": true' "$o/r.json"
grep -q '"nis_mean"' "$o/r.json"
# Filter only, no derivatives, to stdout; angles wrap to [0, 360) for azimuth.
rk-smooth singer -i "$d/located.csv" --columns az_deg,el_deg,range_m --no-smooth --no-derivatives -o - > "$o/loc.csv"
head -1 "$o/loc.csv" | grep -qx 't_s,kind,az_deg,el_deg,range_m,status'
awk -F, '$1 == "0.250000000" { if ($2 != "estimate" || $3 < 359.49 || $3 > 359.51 || $4 < 19.74 || $4 > 19.76 || $6 != "predicted") exit 1; f = 1 } END { exit !f }' "$o/loc.csv"
awk -F, '$1 == "1.000000000" { if ($3 < 0.99 || $3 > 1.01 || $5 < 40.99 || $5 > 41.01 || $6 != "ok") exit 1; f = 1 } END { exit !f }' "$o/loc.csv"
# No negative value anywhere (azimuth wrapped into [0, 360)); `if` so that set -e cannot skip the check.
if grep -q ',-' "$o/loc.csv"; then echo "negative value in $o/loc.csv" >&2; exit 1; fi
rk-smooth singer -i "$d/located.csv" --columns az_deg --accel-sigma 5 --meas-sigma 0.001 --maneuver-time 3 -o "$o/az.csv"
head -1 "$o/az.csv" | grep -qx 't_s,kind,az_deg,status,az_rate_deg_s,az_accel_deg_s2'
awk -F, 'NR > 3 && NR < 28 { if ($5 < 1.99 || $5 > 2.01) exit 1 }' "$o/az.csv"
echo ok
