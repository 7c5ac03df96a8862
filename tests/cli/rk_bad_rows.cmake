# CLI tests of --bad-rows (every tool that reads CSV) and of the report of a failed run (--report on
# every tool). Each test uses another tool's fixture; scripts get $1 = RK_CLI_DATA, $2 = expect.sh and
# source tests/cli/bad_rows.sh (dirty, report_ok, fails). For --bad-rows skip the check is always the
# same: a copy of the input with bad rows added (bad_rows.sh `dirty`) and --bad-rows skip gives
# byte-identical output to the clean input, the report counts the rows skipped, stderr names each
# one, and without the option the tool still stops at the first with exit 3 and file:line:col.
set(RK_BAD_ROWS_LIB ${CMAKE_CURRENT_SOURCE_DIR}/bad_rows.sh)
function(rk_bad_rows_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
       "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n. ${RK_BAD_ROWS_LIB}\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_bad_rows_script(rk_bad_rows_locate [==[
d=$data/locate; w=$data/bad_rows/locate; rm -rf "$w"; mkdir -p "$w"
nt=$(dirty "$d/track.csv" "$w/track.csv" x_px)
nu=$(dirty "$d/turret.csv" "$w/turret.csv" el_deg)
nr=$(dirty "$d/range.csv" "$w/range.csv" range_m)
cam=(--camera "$d/camera.json")
rk-locate --track "$d/track.csv" --turret "$d/turret.csv" --range "$d/range.csv" "${cam[@]}" -o "$w/clean.csv" -q
rk-locate --track "$w/track.csv" --turret "$w/turret.csv" --range "$w/range.csv" "${cam[@]}" -o "$w/skip.csv" \
  --bad-rows skip --report "$w/rep.json" 2> "$w/err"
cmp "$w/clean.csv" "$w/skip.csv"
report_ok "$w/rep.json" track "$nt" turret "$nu" range "$nr"
test "$(grep -c '^rk-locate: warning: .*:[0-9][0-9]*:[0-9][0-9]*: skipped bad row: ' "$w/err")" = $((nt + nu + nr))
grep -q "^rk-locate: warning: $w/turret.csv:[0-9]*:[0-9]*: skipped bad row: column 'el_deg': 'abc' is not a number" "$w/err"
grep -q "skipped bad row: column 't_s' goes backwards" "$w/err"
# --quiet: no warnings, same counts.
rk-locate --track "$w/track.csv" --turret "$w/turret.csv" "${cam[@]}" -o "$w/q.csv" --bad-rows skip -q 2> "$w/err_q"
test ! -s "$w/err_q"
# Strict by default and with --bad-rows error.
"$expect" 3 "$w/x.csv" 'track.csv:4:[0-9]+: row has 1 fields' -- rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv"
"$expect" 3 "$w/x.csv" 'turret.csv:[0-9]+:[0-9]+:' -- rk-locate --track "$d/track.csv" --turret "$w/turret.csv" "${cam[@]}" -o "$w/x.csv" --bad-rows error
"$expect" 2 "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --bad-rows maybe
# Failure reports: bad input (3), usage errors after and during parsing (2), unreadable input (4).
fails 3 "$w/r3.json" "$w/x.csv" "$w/track.csv" -- rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --range-max-gap 0 --report "$w/r2.json"
fails 2 "$w/r2p.json" "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report="$w/r2p.json" --bogus
fails 4 "$w/r4.json" "$w/x.csv" -- rk-locate --track "$w/no_such.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/r4.json"
# A failed run's report never replaces an input, nor the output it names.
cp "$d/turret.csv" "$w/turret_copy.csv"; cp "$w/clean.csv" "$w/clean_copy.csv"
rc=0; rk-locate --track "$w/track.csv" --turret "$w/turret_copy.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/turret_copy.csv" 2> /dev/null || rc=$?
test "$rc" = 3 && cmp "$d/turret.csv" "$w/turret_copy.csv"
rc=0; rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/clean_copy.csv" --report "$w/clean_copy.csv" 2> /dev/null || rc=$?
test "$rc" = 2 && cmp "$w/clean.csv" "$w/clean_copy.csv"
# A report that cannot be written does not change the exit code.
rc=0; rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/no_dir/r.json" 2> "$w/err_nr" || rc=$?
test "$rc" = 3 && grep -q '^rk-locate: warning: the report .* was not written' "$w/err_nr"
echo ok
]==] REQUIRES locate_data)

rk_bad_rows_script(rk_bad_rows_extract [==[
d=$data/extract; w=$data/bad_rows/extract; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$d/frames.csv" frame)
skip_same "$w" frames "$n" -- rk-extract beacon --video "$d/beacon.mkv" --frames @frames.csv
rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames.csv" -o "$w/skip2.csv" --bad-rows skip 2> "$w/err"
test "$(grep -c 'skipped bad row' "$w/err")" = "$n"
"$expect" 3 "$w/x.csv" 'frames.csv:4:[0-9]+:' -- rk-extract beacon --video "$d/beacon.mkv" --frames "$w/frames.csv" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$d/frames_text.csv" -- rk-extract beacon --video "$d/beacon.mkv" --frames "$d/frames_text.csv" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-extract beacon --video "$d/beacon.mkv" --frames "$d/frames.csv" -o "$w/x.csv" --bogus --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-extract --report "$w/r4.json" beacon --video "$w/no_such.mkv" --fps 20 -o "$w/x.csv"
echo ok
]==] REQUIRES extract_inputs)

rk_bad_rows_script(rk_bad_rows_extract_features [==[
d=$data/att_small; w=$data/bad_rows/features; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$d/att/frames.csv" t_s)
skip_same "$w" frames "$n" -- rk-extract features --video "$d/att/video.mkv" --frames @frames.csv --target "$d/target.json"
echo ok
]==] REQUIRES sim_attitude_small)

rk_bad_rows_script(rk_bad_rows_extract_silhouette [==[
T=$data/theo_trial; w=$data/bad_rows/silhouette; rm -rf "$w"; mkdir -p "$w"
n=$(dirty_in "$w" "$T/theo/frames.csv" t_s)
skip_same "$w" frames "$n" -- rk-extract silhouette --video "$T/theo/%06d.png" --frames @frames.csv
echo ok
]==] REQUIRES sim_theodolite_trial)

rk_bad_rows_script(rk_bad_rows_smooth [==[
d=$data/aukf; w=$data/bad_rows/smooth; rm -rf "$w"; mkdir -p "$w"
n=$(dirty "$d/in.csv" "$w/in.csv" yaw_deg)
awk 'BEGIN { print "t_s,frame"; for (k = 0; k < 12; k++) printf "%.3f,%d\n", 0.25 * k, k }' > "$w/at_clean.csv"
na=$(dirty "$w/at_clean.csv" "$w/at.csv" frame)
for sub in aukf singer resample; do
  extra=(); [ $sub = resample ] && extra=(--rate 10)
  rk-smooth $sub -i "$d/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/$sub.clean.csv" -q
  rk-smooth $sub -i "$w/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/$sub.skip.csv" --bad-rows skip --report "$w/$sub.json" -q
  cmp "$w/$sub.clean.csv" "$w/$sub.skip.csv"
  report_ok "$w/$sub.json" input "$n"
  "$expect" 3 "$w/x.csv" 'in.csv:4:[0-9]+:' -- rk-smooth $sub -i "$w/in.csv" --columns yaw_deg,x_m "${extra[@]}" -o "$w/x.csv"
done
# resample --at: its own bad rows too ("frame" is copied through, so "abc" there is not a bad row).
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at_clean.csv" -o "$w/at.clean.csv" -q
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at.csv" -o "$w/at.skip.csv" --bad-rows skip --report "$w/at.json" -q
awk -F, 'NF == 2 && $1 != "nan" && $1 !~ /^-/' "$w/at.csv" > "$w/at_kept.csv"   # the 4 bad rows out, abc/inf kept
test "$(grep -c '' "$w/at_kept.csv")" = 15
rk-smooth resample -i "$d/in.csv" --columns yaw_deg --at "$w/at_kept.csv" -o "$w/at.kept.csv" -q
cmp "$w/at.kept.csv" "$w/at.skip.csv"
report_ok "$w/at.json" at $((na - 2))
fails 3 "$w/r3.json" "$w/x.csv" "$d/text.csv" -- rk-smooth aukf -i "$d/text.csv" --columns yaw_deg -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-smooth aukf -i "$d/in.csv" -o "$w/x.csv" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-smooth singer -i "$w/no_such.csv" --columns yaw_deg -o "$w/x.csv" --report "$w/r4.json"
echo ok
]==] REQUIRES smooth_aukf_data)

rk_bad_rows_script(rk_bad_rows_attitude [==[
d=$data/att_small; w=$data/bad_rows/attitude; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$d/truth/points.csv" y_px)
nu=$(dirty_in "$w" "$d/turret.csv" az_deg)
a=(--camera "$d/att/camera.json" --target "$d/target.json")
skip_same "$w" points "$np" turret "$nu" -- rk-attitude oi --points @points.csv --turret @turret.csv "${a[@]}"
"$expect" 3 "$w/x.csv" 'points.csv:4:[0-9]+:' -- rk-attitude oi --points "$w/points.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$w/points.csv" -- rk-attitude oi --points "$w/points.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-attitude oi --points "$d/truth/points.csv" --turret "$d/turret.csv" --boresight 10,5 "${a[@]}" -o "$w/x.csv" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-attitude oi --points "$w/no_such.csv" --turret "$d/turret.csv" "${a[@]}" -o "$w/x.csv" --report "$w/r4.json"
echo ok
]==] REQUIRES sim_attitude_small)

rk_bad_rows_script(rk_bad_rows_attitude_cylinder [==[
T=$data/theo_trial; w=$data/bad_rows/cylinder; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$T/points.csv" x_px)
nu=$(dirty_in "$w" "$T/theodolite.csv" el_deg)
a=(--camera "$T/theo/camera.json" --target "$T/target.json")
skip_same "$w" points "$np" theodolite "$nu" -- rk-attitude cylinder --points @points.csv --theodolite @theodolite.csv "${a[@]}"
"$expect" 3 "$w/x.csv" 'theodolite.csv:[0-9]+:[0-9]+:' -- rk-attitude cylinder --points "$T/points.csv" --theodolite "$w/theodolite.csv" "${a[@]}" -o "$w/x.csv"
echo ok
]==] REQUIRES sim_theodolite_trial)

rk_bad_rows_script(rk_bad_rows_register [==[
d=$data/radar3; w=$data/bad_rows/register; rm -rf "$w"; mkdir -p "$w"
np=$(dirty_in "$w" "$d/plots.csv" az_deg)
nn=$(dirty_in "$w" "$d/nav.csv" yaw_deg)
skip_same "$w" plots "$np" nav "$nn" -- rk-register kf --plots @plots.csv --nav @nav.csv
"$expect" 3 "$w/x.csv" 'nav.csv:[0-9]+:[0-9]+:' -- rk-register kf --plots "$d/plots.csv" --nav "$w/nav.csv" -o "$w/x.csv"
fails 3 "$w/r3.json" "$w/x.csv" "$w/plots.csv" -- rk-register bernoulli --plots "$w/plots.csv" --nav "$d/nav.csv" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-register kf --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$w/x.csv" --bogus --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.csv" -- rk-register batch --plots "$d/plots.csv" --nav "$w/no_such.csv" -o "$w/x.csv" --report "$w/r4.json"
echo ok
]==] REQUIRES sim_radar_data)

rk_bad_rows_script(rk_bad_rows_analyze [==[
d=$data/analyze; w=$data/bad_rows/analyze; rm -rf "$w"; mkdir -p "$w"
ne=$(dirty "$d/est.csv" "$w/est.csv" range_m)
nr=$(dirty "$d/ref.csv" "$w/ref.csv" az_deg)
c=(--columns az_deg,range_m)
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/clean.json" --errors "$w/clean.csv" -q
rk-analyze compare --estimate "$w/est.csv" --reference "$w/ref.csv" "${c[@]}" -o "$w/skip.json" --errors "$w/skip.csv" \
  --bad-rows skip --report "$w/rep.json" -q
cmp "$w/clean.csv" "$w/skip.csv"
python3 -c 'import json,sys; a, b = (json.load(open(f)) for f in sys.argv[1:]); assert a["columns"] == b["columns"] and a["rows"] == b["rows"]' \
  "$w/clean.json" "$w/skip.json"
report_ok "$w/rep.json" estimate "$ne" reference "$nr"
"$expect" 3 "$w/x.json" 'est.csv:[0-9]+:[0-9]+:' -- rk-analyze compare --estimate "$w/est.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/x.json"
fails 3 "$w/r3.json" "$w/x.json" "$d/est_text.csv" -- rk-analyze compare --estimate "$d/est_text.csv" --reference "$d/ref.csv" --columns range_m -o "$w/x.json" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.json" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" "${c[@]}" --interp quintic -o "$w/x.json" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.json" -- rk-analyze compare --estimate "$w/no_such.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/x.json" --report "$w/r4.json"
echo ok
]==] REQUIRES analyze_data)

# Tools that read no CSV still write the report of a failed run: rk-sim, rk-capture, rk-run.
rk_bad_rows_script(rk_failure_report_sim_capture_run [==[
w=$data/bad_rows/misc; rm -rf "$w"; mkdir -p "$w/trial"
printf '{"width_px": 640, "height_px": [' > "$w/bad.json"
fails 3 "$w/s3.json" "$w/sim3" "$w/bad.json" -- rk-sim beacon --out "$w/sim3" --camera "$w/bad.json" --duration 1 --report "$w/s3.json"
fails 2 "$w/s2.json" "$w/sim2" -- rk-sim beacon --out "$w/sim2" --bogus --report "$w/s2.json"
# (rk-sim checks that --camera exists while parsing: exit 2; its I/O error is an output it cannot write.)
fails 2 "$w/s2c.json" "$w/sim2" -- rk-sim beacon --out "$w/sim2" --camera "$w/no_such.json" --duration 1 --report "$w/s2c.json"
fails 4 "$w/s4.json" "$w/bad.json/sim4" -- rk-sim beacon --out "$w/bad.json/sim4" --duration 1 --report "$w/s4.json"
fails 3 "$w/c3.json" "$w/cap3" "$w/bad.json" -- rk-capture --config "$w/bad.json" --out "$w/cap3" --duration 1 --report "$w/c3.json"
fails 2 "$w/c2.json" "$w/cap2" -- rk-capture --config "$w/bad.json" --report "$w/c2.json"
fails 4 "$w/c4.json" "$w/cap4" -- rk-capture --config "$w/no_such.json" --out "$w/cap4" --duration 1 --report "$w/c4.json"
cp "$w/bad.json" "$w/trial/trial.json"
fails 3 "$w/r3.json" "$w/trial/out" -- rk-run "$w/trial" --report "$w/r3.json"
# The summary rk-run wrote names the manifest; the failure report does not list it twice.
python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); n = sum(1 for v in r["inputs"].values() if v == sys.argv[2] or (isinstance(v, dict) and v.get("path") == sys.argv[2])); assert n == 1, r["inputs"]' \
  "$w/r3.json" "$w/trial/trial.json"
fails 2 "$w/r2.json" "$w/trial/out" -- rk-run "$w/trial" --jobs 0 --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/trial/out" -- rk-run "$w/no_such_trial" --report "$w/r4.json"
echo ok
]==])
