#!/usr/bin/env bash
# CLI test rk_sim_radar_options: registered, and described, in tests/cli/rk_sim_radar.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
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
