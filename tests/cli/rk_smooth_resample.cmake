# CLI tests of rk-smooth resample (SPEC.md §1.1, §4). The fixture smooth_resample_data writes
# small inputs to ${RK_CLI_DATA}/resample; every other test here REQUIRES it. Scripts get
# $1 = RK_CLI_DATA, $2 = expect.sh; rk-smooth is found on PATH (RK_BIN first).
function(rk_smooth_resample_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_smooth_resample_script(rk_smooth_resample_data [==[
d=$data/resample; rm -rf "$d"; mkdir -p "$d"
# 5 Hz range log from 0.1 s to 5.9 s, range = 40 + 2 t; one device-error row (status 7, at
# 1.1 s: bridged) and a hole from 2.9 to 4.1 s (longer than the default gap limit 0.5 s).
awk 'BEGIN { print "# range log"; print "t_s,range_m,status"; for (k = 0; k < 30; k++) { t = 0.1 + 0.2 * k;
  if (t > 3.05 && t < 4.05) continue;
  if (k == 5) printf "%.3f,,7\n", t; else printf "%.3f,%.6f,0\n", t, 40 + 2 * t } }' > "$d/range.csv"
# 20 Hz frames from 0 to 6 s.
awk 'BEGIN { print "frame,t_s"; for (k = 0; k <= 120; k++) printf "%d,%.3f\n", k, 0.05 * k }' > "$d/frames.csv"
printf 'frame,time\n0,0.1\n1,0.2\n' > "$d/frames_not.csv"
printf 'frame,t_s\n0,0.1\n1,0.3\n2,0.2\n' > "$d/frames_back.csv"
printf 'frame,t_s\n0,0.1\n1,x\n' > "$d/frames_text.csv"
printf 't_s,range_m\n0,1\n0.2,2\n' > "$d/two.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.2,3\n0.4,4\n' > "$d/dup.csv"
printf 't_s,range_m\n0,1\n0.2,2\n0.4,1e\n0.6,4\n' > "$d/text.csv"
echo ok
]==] SETUP smooth_resample_data)

rk_smooth_resample_script(rk_smooth_resample_good [==[
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
]==] REQUIRES smooth_resample_data)

rk_smooth_resample_script(rk_smooth_resample_bad [==[
d=$data/resample; o=$d/bad; rm -rf "$o"; mkdir -p "$o"
r="$d/range.csv"; f="$d/frames.csv"
$expect 3 "$o/x.csv" 'two.csv' -- rk-smooth resample -i "$d/two.csv" --columns range_m --at "$f" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'dup.csv:4:' -- rk-smooth resample -i "$d/dup.csv" --columns range_m --at "$f" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'text.csv:4:' -- rk-smooth resample -i "$d/text.csv" --columns range_m --rate 5 -o "$o/x.csv"
$expect 3 "$o/x.csv" 'range.csv:2:.*range_mm' -- rk-smooth resample -i "$r" --columns range_mm --rate 5 -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_not.csv:1:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_not.csv" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_back.csv:4:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_back.csv" -o "$o/x.csv"
$expect 3 "$o/x.csv" 'frames_text.csv:3:' -- rk-smooth resample -i "$r" --columns range_m --at "$d/frames_text.csv" -o "$o/x.csv"
$expect 4 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$d/none.csv" -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 0 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate -5 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$f" --rate 5 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --method spline -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --max-gap 0 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --rate 5 --margin -1 -o "$o/x.csv"
$expect 2 "$o/x.csv" -- rk-smooth resample -i "$r" --columns range_m --at "$f" --t0 1 -o "$o/x.csv"
$expect 2 - -- rk-smooth resample -i "$r" --columns range_m --at "$f" -o "$f"
echo ok
]==] REQUIRES smooth_resample_data)
