# CLI tests of rk-smooth singer (SPEC.md §1.1, §4). The fixture smooth_singer_data writes
# small inputs to ${RK_CLI_DATA}/singer; every other test here REQUIRES it. Scripts get
# $1 = RK_CLI_DATA, $2 = expect.sh; rk-smooth is found on PATH (RK_BIN first).
function(rk_smooth_singer_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_smooth_singer_script(rk_smooth_singer_data [==[
d=$data/singer; rm -rf "$d"; mkdir -p "$d"
# 5 Hz range log, 1 m/s + 0.2 m/s^2, one device-error row (status 7) and one masked value.
awk 'BEGIN { print "t_s,range_m,status"; for (k = 0; k < 40; k++) { t = 0.2 * k;
  if (k == 10) printf "%.3f,,7\n", t; else if (k == 20) printf "%.3f,999.0,3\n", t;
  else printf "%.3f,%.6f,0\n", t, 50 + t + 0.1 * t * t } }' > "$d/range.csv"
# Located-like file: azimuth through north, elevation, tool statuses, one lost row.
awk 'BEGIN { print "frame,t_s,az_deg,el_deg,range_m,status"; for (k = 0; k < 30; k++) { t = 0.05 * k;
  a = 359 + 2 * t; if (a >= 360) a -= 360;
  if (k == 5) printf "%d,%.3f,,,,lost\n", k, t; else printf "%d,%.3f,%.6f,%.6f,%.6f,ok\n", k, t, a, 20 - t, 40 + t } }' > "$d/located.csv"
printf 't_s,range_m\n0,1\n0.1,2\n' > "$d/two.csv"
printf 't_s,range_m\n0,1\n0.1,2\n0.1,3\n0.3,4\n' > "$d/dup.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.1,3\n0.3,4\n' > "$d/back.csv"
printf 't_s,range_m\n0,1\n0.1,2\n0.2,abc\n0.3,4\n' > "$d/text.csv"
printf 't_s,range_m\n0,1\n0.1,\n0.2,\n0.3,\n0.4,5\n' > "$d/sparse.csv"
printf 't_s,range_m,status\n0,1,0\n0.1,2,0\n0.2,3,bad\n0.3,4,0\n' > "$d/badstatus.csv"
echo ok
]==] SETUP smooth_singer_data)

rk_smooth_singer_script(rk_smooth_singer_good [==[
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
! grep -q ',-' "$o/loc.csv"
rk-smooth singer -i "$d/located.csv" --columns az_deg --accel-sigma 5 --meas-sigma 0.001 --maneuver-time 3 -o "$o/az.csv"
head -1 "$o/az.csv" | grep -qx 't_s,kind,az_deg,status,az_rate_deg_s,az_accel_deg_s2'
awk -F, 'NR > 3 && NR < 28 { if ($5 < 1.99 || $5 > 2.01) exit 1 }' "$o/az.csv"
echo ok
]==] REQUIRES smooth_singer_data)

# Bad input: SPEC.md §4 exit codes, one-line errors naming file:line:col, no output.
rk_smooth_singer_script(rk_smooth_singer_bad [==[
d=$data/singer; o=$d/bad; rm -rf "$o"; mkdir -p "$o"
$expect 3 "$o/x.csv" 'two.csv' -- rk-smooth singer -i "$d/two.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'dup.csv:4:' -- rk-smooth singer -i "$d/dup.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'back.csv:4:' -- rk-smooth singer -i "$d/back.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'text.csv:4:' -- rk-smooth singer -i "$d/text.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'sparse.csv' -- rk-smooth singer -i "$d/sparse.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'badstatus.csv:4:' -- rk-smooth singer -i "$d/badstatus.csv" --columns range_m -o "$o/x.csv"
$expect 3 "$o/x.csv" 'range.csv:1:.*speed_m' -- rk-smooth singer -i "$d/range.csv" --columns speed_m -o "$o/x.csv"
$expect 4 "$o/x.csv" -- rk-smooth singer -i "$d/nonexistent.csv" --columns range_m -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --maneuver-time 0
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --meas-sigma -1
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --accel-sigma 1,2
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$o/x.csv" --accel-sigma abc
$expect 2 "$o/x.csv" 'accel-sigma' -- rk-smooth singer -i "$d/range.csv" --columns status -o "$o/x.csv"  # no unit
$expect 2 "$o/x.csv" -- rk-smooth singer -i "$d/range.csv" -o "$o/x.csv"
$expect 2 - -- rk-smooth singer -i "$d/range.csv" --columns range_m -o "$d/range.csv"
echo ok
]==] REQUIRES smooth_singer_data)
