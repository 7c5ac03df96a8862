# CLI tests of rk-register bernoulli|kf|batch (SPEC.md §1.1, §2.1, §4; docs/rk-register.md). They
# REQUIRE the fixture sim_radar_data (rk_sim_radar.cmake: ${RK_CLI_DATA}/radar3, scenario 3, 80
# scans). Scripts get $1 = RK_CLI_DATA, $2 = expect.sh; rk-register is on PATH.
function(rk_register_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_register_script(rk_register_good [==[
d=$data/radar3; o=$data/register; rm -rf "$o"; mkdir -p "$o"
hdr='t_s,a_range_m,a_az_deg,a_el_deg,a_yaw_deg,a_pitch_deg,a_roll_deg,b_range_m,b_az_deg,b_el_deg,b_yaw_deg,b_pitch_deg,b_roll_deg,status'
for m in bernoulli kf batch; do
  out=$(rk-register $m --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$o/$m.csv" --report "$o/$m.json")
  test -z "$out"
  test "$(head -n 1 "$o/$m.csv")" = "$hdr"
  rk-register $m --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$o/${m}_s.csv" --sigmas
  test "$(grep -c '' "$o/$m.csv")" = 81                # header + one row per scan
done
python3 - "$o" "$d/truth/biases.csv" <<'PY'
import csv, json, sys, math
o, truth = sys.argv[1], list(csv.DictReader(open(sys.argv[2])))[0]
for m in ('bernoulli', 'kf', 'batch'):
    rows = list(csv.DictReader(open(f'{o}/{m}.csv')))
    assert all(r['status'] == 'ok' for r in rows[1:]), m
    last = rows[-1]
    # 80 scans of scenario 3 are not enough to converge (the benchmark measures accuracy): each
    # estimate must be within 4.5 reported sigmas of the truth (units, signs, columns, consistency),
    # and the range sigma already below 30 m.
    sig = list(csv.DictReader(open(f'{o}/{m}_s.csv')))[-1]
    for k, v in truth.items():
        if k == 't_s': continue
        s = float(sig[k.replace('_m', '_sigma_m') if k.endswith('_m') else k.replace('_deg', '_sigma_deg')])
        assert abs(float(last[k]) - float(v)) <= 4.5 * s, (m, k, last[k], v, s)
        if k.endswith('range_m'): assert s < 30, (m, k, s)
    rep = json.load(open(f'{o}/{m}.json'))
    for k in ('tool', 'version', 'command_line', 'inputs', 'subcommand', 'radars', 'input', 'options',
              'estimate', 'sigma', 'correlation', 'stats', 'rows_written'):
        assert k in rep, (m, k)
    assert rep['radars'] == ['a', 'b'] and rep['rows_written'] == 80
    assert rep['input']['steps'] == 80 and rep['stats']['covariance_repairs'] == 0 if m != 'batch' else True
    assert abs(rep['estimate']['a']['range_m'] - float(last['a_range_m'])) < 1e-6
    assert len(rep['correlation']['matrix']) == 12
b = json.load(open(f'{o}/batch.json'))
assert b['stats']['covariance_ok'] and 0.7 < b['stats']['variance_factor'] < 1.3, b['stats']
assert 'initial_bernoulli' in b
PY
# stdout, sigma columns, the paper's linearisation, no partition, one track for kf, other association
rk-register bernoulli --plots "$d/plots.csv" --nav "$d/nav.csv" -o - --sigmas -L 1 --linearize measured > "$o/stdout.csv"
head -n 1 "$o/stdout.csv" | grep -q ',status,a_range_sigma_m,a_az_sigma_deg,'
test "$(grep -c '' "$o/stdout.csv")" = 81
rk-register kf --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$o/kf4.csv" --track 4 --report "$o/kf4.json"
grep -q '"track": "4"' "$o/kf4.json"
rk-register batch --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$o/bt.csv" --associate track --loss none -q
rk-register batch --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$o/bb.csv" --associate bernoulli --loss cauchy -q
# Plots read from stdin; comment lines and extra columns are fine.
(echo '# a comment'; cat "$d/plots.csv") | awk -F, 'BEGIN{OFS=","} {print $0 (NR==2 ? ",snr_db" : ",7")}' |
  sed 's/^# a comment,7$/# a comment/' | rk-register bernoulli --plots - --nav "$d/nav.csv" -o "$o/stdin.csv"
cmp "$o/stdin.csv" "$o/bernoulli.csv"
rk-register --help | grep -q bernoulli
rk-register bernoulli --help | grep -q -- '--subset-length'
echo ok
]==] REQUIRES sim_radar_data)

# Radar b reports 0.3 s after radar a, and the nav is a 1 Hz log: steps pair by time, nav is
# interpolated; rows carry the later time.
rk_register_script(rk_register_time_offset [==[
d=$data/radar_off; rm -rf "$d"
rk-sim radar --out "$d" --scenario 1 --steps 40 --seed 2 --time-offset-b 0.3 --nav-rate 1
rk-register bernoulli --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$d/b.csv" --report "$d/b.json"
test "$(grep -c '' "$d/b.csv")" = 41
sed -n 2p "$d/b.csv" | grep -q '^0.300000000,'
grep -q '"max_pair_offset_s": 0.3' "$d/b.json"
# A tolerance below the offset pairs nothing: exit 1 with the offset in the message, no output.
"$expect" 1 "$d/b0.csv" "typically 0.3 s after radar 'a'.*raise --pair-tol" -- \
  rk-register bernoulli --plots "$d/plots.csv" --nav "$d/nav.csv" -o "$d/b0.csv" --pair-tol 0.1
echo ok
]==])

rk_register_script(rk_register_bad_input [==[
d=$data/radar3; o=$data/register_bad; rm -rf "$o"; mkdir -p "$o"
P=$d/plots.csv; N=$d/nav.csv; x=$o/x.csv
# Plots without nav at their time: nav stops at t = 200 s.
awk -F, 'NR == 1 || $1 + 0 <= 200' "$N" > "$o/nav_short.csv"
$expect 3 "$x" 'plots.csv:[0-9]+:1: .*no nav of radar .a. at t_s = 205' -- rk-register bernoulli --plots "$P" --nav "$o/nav_short.csv" -o "$x"
# One radar missing from the plots.
grep -v ',b,' "$P" > "$o/only_a.csv"
$expect 3 "$x" "only_a.csv: no plots of radar 'b'" -- rk-register bernoulli --plots "$o/only_a.csv" --nav "$N" -o "$x"
# Unknown radar name (line 5 renamed).
awk -F, 'BEGIN{OFS=","} NR == 5 {$2 = "c"} {print}' "$P" > "$o/radar_c.csv"
$expect 3 "$x" "radar_c.csv:5:[0-9]+: .*unknown radar 'c'" -- rk-register kf --plots "$o/radar_c.csv" --nav "$N" -o "$x"
# A third radar in the nav.
(cat "$N"; echo '400,c,25,110,0,0,0,0') > "$o/nav3.csv"
$expect 3 "$x" "nav3.csv:162:[0-9]+: .*third radar 'c'" -- rk-register batch --plots "$P" --nav "$o/nav3.csv" -o "$x"
# NaN value.
awk -F, 'BEGIN{OFS=","} NR == 7 {$4 = "NaN"} {print}' "$P" > "$o/nan.csv"
$expect 3 "$x" 'nan.csv:7:[0-9]+: .*not a finite number' -- rk-register bernoulli --plots "$o/nan.csv" --nav "$N" -o "$x"
# Times out of order (lines 30 and 200 swapped).
awk 'NR == FNR {l[FNR] = $0; next} FNR == 30 {print l[200]; next} FNR == 200 {print l[30]; next} {print}' "$P" "$P" > "$o/order.csv"
$expect 3 "$x" 'order.csv:(30|31):1: .*backwards' -- rk-register bernoulli --plots "$o/order.csv" --nav "$N" -o "$x"
# kf without track_id.
cut -d, -f1-5 "$P" > "$o/no_id.csv"
$expect 3 "$x" "no_id.csv:1:1: .*track_id" -- rk-register kf --plots "$o/no_id.csv" --nav "$N" -o "$x"
$expect 3 "$x" "no_id.csv:1:1: .*track_id" -- rk-register batch --associate track --plots "$o/no_id.csv" --nav "$N" -o "$x"
rk-register bernoulli --plots "$o/no_id.csv" --nav "$N" -o "$o/ok.csv"   # bernoulli does not need it
# Usage errors (2), I/O errors (4), output never replaces an input.
$expect 2 "$x" 'linearize' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$x" --linearize paper
$expect 2 "$x" 'subset length' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$x" -L 0
$expect 2 "$x" 'p0: give six values' -- rk-register kf --plots "$P" --nav "$N" -o "$x" --p0 1,2,3,4,5
$expect 2 "$x" 'no plot has this track_id' -- rk-register kf --plots "$P" --nav "$N" -o "$x" --track 9
$expect 2 "$x" 'both be stdin' -- rk-register kf --plots - --nav - -o "$x"
$expect 2 "$x" 'subcommand' -- rk-register --plots "$P" --nav "$N" -o "$x"
$expect 4 "$x" 'nothere.csv' -- rk-register bernoulli --plots "$o/nothere.csv" --nav "$N" -o "$x"
$expect 4 - '' -- rk-register bernoulli --plots "$P" --nav "$N" -o "$o/nodir/x.csv"
cp "$P" "$o/same.csv"
$expect 2 - 'input' -- rk-register bernoulli --plots "$o/same.csv" --nav "$N" -o "$o/same.csv"
cmp "$o/same.csv" "$P"
echo ok
]==] REQUIRES sim_radar_data)
