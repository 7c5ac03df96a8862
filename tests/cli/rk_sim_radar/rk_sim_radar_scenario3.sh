#!/usr/bin/env bash
# CLI test rk_sim_radar_scenario3: registered, and described, in tests/cli/rk_sim_radar.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/radar3
out=$(rk-sim radar --out "$d" --force --scenario 3 --steps 80 --seed 1 --report "$data/radar3.json")
test -z "$out"
for f in plots.csv nav.csv truth/biases.csv truth/targets.csv truth/platforms.csv scenario.json; do
  test -s "$d/$f" || { echo "missing $f"; exit 1; }
done
test "$(head -n 1 "$d/plots.csv")" = "t_s,radar,range_m,az_deg,el_deg,track_id"
test "$(head -n 1 "$d/nav.csv")" = "t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg"
test "$(head -n 1 "$d/truth/biases.csv")" = "t_s,a_range_m,a_az_deg,a_el_deg,a_yaw_deg,a_pitch_deg,a_roll_deg,b_range_m,b_az_deg,b_el_deg,b_yaw_deg,b_pitch_deg,b_roll_deg"
test "$(grep -c '' "$d/nav.csv")" = 161                 # header + 2 radars x 80 scans
test "$(grep -c ',a,' "$d/plots.csv")" -ge 400          # 5 targets per scan + clutter
test "$(grep -c ',$' "$d/plots.csv")" -ge 500           # clutter: empty track_id (Poisson 5 x 160 scans)
# Truth biases in file units: radar a range 1200 m, azimuth 0.0105 rad = 0.601605685 deg.
sed -n 2p "$d/truth/biases.csv" | grep -q '^0.000000000,1200.000000000,0.601605685,'
# Nav at t = 5 s of radar a: yaw = 0.002*5 + 0.0105 rad = 1.174563...deg.
grep '^5.000000000,a,' "$d/nav.csv" | grep -q ',1.174563'
python3 - "$d/plots.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r['t_s']) for r in rows]
assert all(b >= a for a, b in zip(t, t[1:])), 'plots not in time order'
assert all(0 <= float(r['az_deg']) < 360 for r in rows)
assert all(-90 <= float(r['el_deg']) <= 90 for r in rows)
assert {r['radar'] for r in rows} == {'a', 'b'}
ids = [r['track_id'] for r in rows[:12] if r['radar'] == 'a']
assert ids != sorted(ids), 'plots of a scan should be shuffled'
PY
grep -q '"clutter_plots"' "$data/radar3.json"
grep -q '"lat_deg": 25' "$d/scenario.json"
echo ok
