# CLI tests of rk-sim radar (seed 002 scenarios; docs/rk-sim.md). The fixture sim_radar_data writes
# ${RK_CLI_DATA}/radar3 (scenario 3, 80 scans, seed 1) for rk-register's CLI tests to REQUIRE.
# Shell scripts get $1 = RK_CLI_DATA, $2 = expect.sh; rk-sim is on PATH.
function(rk_sim_radar_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT})
endfunction()

rk_sim_radar_script(rk_sim_radar_scenario3 [==[
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
]==] SETUP sim_radar_data)

# Same seed → same files; another seed differs; options change what they say.
rk_sim_radar_script(rk_sim_radar_options [==[
d=$data/radar_opts; rm -rf "$d"; mkdir -p "$d"
rk-sim radar --out "$d/a" --scenario 2 --steps 10 --seed 3 --pd 0.5 --names ship,plane --time-offset-b 0.25 --nav-rate 2
rk-sim radar --out "$d/b" --scenario 2 --steps 10 --seed 3 --pd 0.5 --names ship,plane --time-offset-b 0.25 --nav-rate 2
rk-sim radar --out "$d/c" --scenario 2 --steps 10 --seed 4 --pd 0.5 --names ship,plane --time-offset-b 0.25 --nav-rate 2
diff -r -x trial.json "$d/a" "$d/b"   # trial.json differs by its name only:
test "$(sed s/\"name\":\ \"a\"/N/ "$d/a/trial.json")" = "$(sed s/\"name\":\ \"b\"/N/ "$d/b/trial.json")"
if cmp -s "$d/a/plots.csv" "$d/c/plots.csv"; then echo "seed has no effect"; exit 1; fi
grep -q '^45.250000000,plane,' "$d/a/plots.csv"        # radar b 0.25 s after radar a
test "$(grep -c '' "$d/a/nav.csv")" = 185              # 2 Hz: 0 ... 45.5 s, 92 times x 2 radars + header
test "$(grep -c ',$' "$d/a/plots.csv")" = 0            # scenario 2: no clutter
n=$(($(grep -c '' "$d/a/plots.csv") - 1)); test "$n" -lt 100   # p_D 0.5: fewer than 2 x 5 x 10 plots
rk-sim radar --out "$d/s" --scenario 1 --steps 3 --index-unit step --targets 7 --clutter 2
test "$(cut -d, -f6 "$d/s/plots.csv" | sort -u | grep -c '^[0-9]')" = 7
grep -q '"index_unit": "step"' "$d/s/scenario.json"
echo ok
]==])

rk_cli_test(rk_sim_radar_bad_scenario COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad1 "scenario" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad1 --scenario 4)
rk_cli_test(rk_sim_radar_bad_pd COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad2 "detection probability" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad2 --pd 0)
rk_cli_test(rk_sim_radar_bad_offset COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad3 "half the scan interval" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad3 --time-offset-b 3)
rk_cli_test(rk_sim_radar_bad_origin COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad4 "origin" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad4 --origin 25,110)
rk_sim_radar_script(rk_sim_radar_refuses_nonempty_out [==[
d=$data/radar_keep; rm -rf "$d"; mkdir -p "$d"; echo precious > "$d/keep.txt"
"$expect" 2 - 'not empty' -- rk-sim radar --out "$d" --steps 2
test "$(ls -A "$d")" = keep.txt || { echo "folder changed"; exit 1; }
if ls -A "$data" | grep -q '^\.radar_keep'; then echo "temporary folder left"; exit 1; fi
f=$data/radar_file; echo x > "$f"
"$expect" 4 "$f/run" -- rk-sim radar --out "$f/run" --steps 2
echo ok
]==])
