# CLI tests of rk-analyze compare (SPEC.md §1.1, §4). The fixture
# analyze_data writes tiny estimate/reference files to ${RK_CLI_DATA}/analyze.
function(rk_analyze_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

# Reference: az through north, range linear. Estimate errors by hand:
#   t=0.5: az 359.99 vs 0.0 → −0.01°, range 101.5 vs 101 → +0.5
#   t=1.5: az 0.25 vs 0.2 → +0.05°,   range 102.9 vs 103 → −0.1
#   t=2.5: az empty (skipped), range outside the reference (skipped)
rk_analyze_script(rk_analyze_data [==[
d=$data/analyze; rm -rf "$d"; mkdir -p "$d"
printf '# reference\nt_s,az_deg,range_m\n0,359.9,100\n1,0.1,102\n2,0.3,104\n' > "$d/ref.csv"
printf 't_s,az_deg,range_m,status\n0.5,359.99,101.5,ok\n# a comment\n1.5,0.25,102.9,ok\n2.5,,105,lost\n' > "$d/est.csv"
printf 't_s,az_deg,range_m\n0.5,359.99,abc\n' > "$d/est_text.csv"
printf 't_s,az_deg,range_m\n0.5,nan,1\n' > "$d/est_nan.csv"
printf 't_s,az_deg,range_m\n1,0,100\n0,0,100\n' > "$d/ref_back.csv"
printf 't_s,range_m\n0,1\n1,2\n' > "$d/ref_noaz.csv"
echo ok
]==] SETUP analyze_data)

rk_analyze_script(rk_analyze_good [==[
d=$data/analyze; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg,range_m \
  -o "$o/stats.json" --errors "$o/errors.csv" --table > "$o/table.txt"
for k in '"tool": "rk-analyze"' '"command_line"' '"inputs"' '"columns"' '"p95_abs"' '"unit": "deg"' '"unit": "m"' \
         '"estimate_empty": 1' '"reference_outside": 1'; do
  grep -q "$k" "$o/stats.json" || { echo "missing $k"; exit 1; }
done
# mean az error = (−0.01 + 0.05)/2 = 0.02; range errors 0.5, −0.1 → max 0.5, min −0.1
python3 - "$o/stats.json" <<'EOF'
import json, math, sys
c = json.load(open(sys.argv[1]))["columns"]
near = lambda a, b: abs(a - b) < 1e-9
a, r = c["az_deg"], c["range_m"]
assert a["n"] == 2 and near(a["max"], 0.05) and near(a["min"], -0.01) and near(a["mean"], 0.02), a
assert near(a["std"], math.sqrt(2 * 0.03 ** 2)) and near(a["rms"], math.sqrt((0.01 ** 2 + 0.05 ** 2) / 2)), a
assert near(a["p95_abs"], 0.01 + 0.95 * 0.04), a
assert r["n"] == 2 and near(r["max"], 0.5) and near(r["min"], -0.1) and near(r["mean"], 0.2), r
assert r["n_skipped"] == {"estimate_empty": 0, "reference_outside": 1, "reference_gap": 0, "time_window": 0}, r
EOF
head -1 "$o/errors.csv" | grep -qx 't_s,err_az_deg,err_range_m'
test "$(grep -c '' "$o/errors.csv")" = 4
grep -q '^2.500000000,,$' "$o/errors.csv"
grep -q '^az_deg .* 2 ' "$o/table.txt"
# --arcsec, --after/--before, stdout, table on stderr with -o -
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg --arcsec --after 1 -o - \
  --table 2> "$o/table_err.txt" > "$o/arcsec.json"
python3 - "$o/arcsec.json" <<'EOF'
import json, sys
a = json.load(open(sys.argv[1]))["columns"]["az_deg"]
assert a["unit"] == "arcsec" and a["n"] == 1 and abs(a["max"] - 180.0) < 1e-6 and a["std"] is None, a
assert a["n_skipped"]["time_window"] == 1, a
EOF
grep -q '^az_deg  *arcsec' "$o/table_err.txt"
# nothing comparable: null statistics and a warning, exit 0
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg --before 0.1 -o "$o/none.json" \
  2> "$o/warn.txt"
grep -q '^rk-analyze: warning: column az_deg' "$o/warn.txt"
python3 -c 'import json, sys; a = json.load(open(sys.argv[1]))["columns"]["az_deg"]; assert a["n"] == 0 and all(a[k] is None for k in ("max", "min", "mean", "std", "rms", "p95_abs")), a' "$o/none.json"
echo ok
]==] REQUIRES analyze_data)

rk_analyze_script(rk_analyze_bad_input [==[
d=$data/analyze; o=$d/bad.json; rm -f "$o"
L() { "$expect" "$@"; }
L 3 "$o" 'ref_noaz.csv:1:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref_noaz.csv" --columns az_deg -o "$o"
L 3 "$o" 'est.csv:1:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns yaw_deg -o "$o"
L 3 "$o" 'est_text.csv:2:[0-9]+:' -- rk-analyze compare --estimate "$d/est_text.csv" --reference "$d/ref.csv" --columns range_m -o "$o"
L 3 "$o" 'est_nan.csv:2:[0-9]+:' -- rk-analyze compare --estimate "$d/est_nan.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 3 "$o" 'ref_back.csv:3:[0-9]+:' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref_back.csv" --columns az_deg -o "$o"
L 4 "$o" 'no_such.csv' -- rk-analyze compare --estimate "$d/no_such.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --bogus
L 2 "$o" -- rk-analyze --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" -o "$o"
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --after 5 --before 1
L 2 "$o" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$o" --interp quintic
L 2 - 'refusing to overwrite' -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg -o "$d/ref.csv"
grep -q '^t_s,az_deg,range_m' "$d/ref.csv"
echo ok
]==] REQUIRES analyze_data)
