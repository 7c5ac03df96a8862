#!/usr/bin/env bash
# CLI test rk_register_two_d: registered, and described, in tests/cli/rk_register.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
o=$data/register_2d; rm -rf "$o"; mkdir -p "$o"
# rk-sim radar --2d: radar b's plots without el_deg; the truth keeps every true bias.
rk-sim radar --out "$o/sim" --scenario 3 --steps 80 --seed 1 --2d
P=$o/sim/plots.csv; N=$o/sim/nav.csv
test "$(awk -F, '$2 == "b" && $5 != ""' "$P" | wc -l)" = 0
test "$(awk -F, '$2 == "a" && $5 == ""' "$P" | wc -l)" = 0
awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) if ($i == "b_el_deg") c = i} NR == 2 {exit !($c != "")}' "$o/sim/truth/biases.csv"
grep -q '"two_d": \[' "$o/sim/scenario.json"
rk-sim radar --out "$o/both" --scenario 1 --steps 5 --2d a,b
test "$(awk -F, 'NR > 1 && $5 != ""' "$o/both/plots.csv" | wc -l)" = 0
$expect 2 "$o/bad" "--2d: 'c' is not a radar name" -- rk-sim radar --out "$o/bad" --2d c
x=$o/x.csv
for m in bernoulli kf batch; do
  rk-register $m --plots "$P" --nav "$N" -o "$o/$m.csv" --sigmas --report "$o/$m.json" 2> "$o/$m.err"
  grep -q "rk-register: warning: radar 'b' is 2-D (no el_deg): its el bias is unobservable" "$o/$m.err"
done
python3 - "$o" "$o/sim/truth/biases.csv" <<'PY'
import csv, json, sys
o, truth = sys.argv[1], list(csv.DictReader(open(sys.argv[2])))[0]
for m in ('bernoulli', 'kf', 'batch'):
    rows = list(csv.DictReader(open(f'{o}/{m}.csv')))
    assert len(rows) == 80, m
    assert all(r['b_el_deg'] == '' and r['b_el_sigma_deg'] == '' for r in rows), m   # empty, not 0 or nan
    last = rows[-1]
    for k, v in truth.items():
        if k == 't_s' or k == 'b_el_deg': continue
        s = float(last[k.replace('_m', '_sigma_m') if k.endswith('_m') else k.replace('_deg', '_sigma_deg')])
        assert abs(float(last[k]) - float(v)) <= 4.5 * s, (m, k, last[k], v, s)
    rep = json.load(open(f'{o}/{m}.json'))
    assert rep['estimate']['b']['el_deg'] is None and rep['sigma']['b']['el_deg'] is None, m
    assert rep['input']['plots_without_el'] == {'a': 0, 'b': rep['input']['plots']['b']}, m
    codes = [w['code'] for w in rep['warnings']]
    assert 'radar_2d_unobservable' in codes, (m, codes)
PY
# Both radars 2-D: refused (exit 1), nothing written.
$expect 1 "$x" 'both radars are 2-D' -- rk-register kf --plots "$o/both/plots.csv" --nav "$o/both/nav.csv" -o "$x"
# rk-import asterix's extra columns are ignored: the same biases.
awk -F, 'BEGIN{OFS=","} NR == 1 {print $0, "sac,sic,flight_level,height_m,mode3a,address,el_source"; next}
         {print $0, "25,10,350,,1234,3C6586,"}' "$P" > "$o/asterix.csv"
rk-register kf --plots "$o/asterix.csv" --nav "$N" -o "$o/kf_asterix.csv" --sigmas 2> /dev/null
cmp "$o/kf_asterix.csv" "$o/kf.csv"
# Malformed: text in a 2-D file's el_deg is still an error at its cell (exit 3).
awk -F, 'BEGIN{OFS=","} NR == 9 {$5 = "high"} {print}' "$P" > "$o/bad_el.csv"
$expect 3 "$x" 'bad_el.csv:9:[0-9]+: .*not a number' -- rk-register bernoulli --plots "$o/bad_el.csv" --nav "$N" -o "$x"
echo ok
