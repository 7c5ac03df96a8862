#!/usr/bin/env bash
# CLI test rk_sim_option_bounds: registered, and described, in tests/cli/rk_sim.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/sim_bounds; rm -rf "$d"; mkdir -p "$d"
# One message form from the option tables ("--flag must be ... unit"), exit 2, nothing written; one
# option of each table (nested tables too: trajectory, sensor, servo, device common options).
"$expect" 2 "$d/b1" '^rk-sim: error: --fps must be in \(0, 1000\] Hz$' -- rk-sim beacon --out "$d/b1" --fps 0
"$expect" 2 "$d/b2" '^rk-sim: error: --max-el-deg must be in \(0, 85\] deg$' -- rk-sim beacon --out "$d/b2" --max-el-deg 90
"$expect" 2 "$d/b3" '^rk-sim: error: --read-noise-dn must be in \[0, 100\] DN$' -- rk-sim beacon --out "$d/b3" --read-noise-dn 101
"$expect" 2 "$d/b4" '^rk-sim: error: --turret-lag-s must be in \[0, 2\] s$' -- rk-sim beacon --out "$d/b4" --turret-lag-s 3
"$expect" 2 "$d/b5" '^rk-sim: error: --jitter-max-hz must be >= --jitter-min-hz$' -- rk-sim beacon --out "$d/b5" --jitter-min-hz 6
"$expect" 2 "$d/b6" 'bit-depth' -- rk-sim beacon --out "$d/b6" --bit-depth 12
"$expect" 2 "$d/a1" '^rk-sim: error: --marker-dn must be in \(0, 255\] DN$' -- rk-sim attitude --out "$d/a1" --no-video --marker-dn 0
"$expect" 2 "$d/a2" '^rk-sim: error: --jitter-arcsec must be in \[0, 2062.65\] arcsec$' -- rk-sim attitude --out "$d/a2" --no-video --jitter-arcsec 3000
"$expect" 2 "$d/r1" '^rk-sim: error: --scenario must be in \[1, 3\]$' -- rk-sim radar --out "$d/r1" --scenario 4
"$expect" 2 "$d/p1" '^rk-sim: error: --noise-m must be in \[0, 1\] m$' -- rk-sim posetrack --out "$d/p1" --noise-m 2
"$expect" 2 "$d/t1" '^rk-sim: error: --sky-dn must be in \[0, 255\] DN$' -- rk-sim theodolite --out "$d/t1" --sky-dn 300
"$expect" 2 "$d/t2" '^rk-sim: error: --el-deg must be in \[-10, 89\] deg$' -- rk-sim theodolite --out "$d/t2" --el-deg 90
"$expect" 2 - '^rk-sim: error: --device-id must be in \[0, 9\]$' -- rk-sim device dimetix --device-id 12 --duration 1
"$expect" 2 - '^rk-sim: error: --error-rate must be in \[0, 1\]$' -- rk-sim device ptu --error-rate 2 --duration 1
"$expect" 2 - '^rk-sim: error: --slew-deg-s must be > 0 deg/s$' -- rk-sim device ptu --slew-deg-s 0 --duration 1
# The report's options come from the tables: keys from the flags (with the unit), values as parsed.
rk-sim beacon --out "$d/ok" --preset small --duration 0.5 --max-el-deg 70 --jitter-min-hz 1 --report "$d/ok.json" --quiet
python3 - "$d/ok.json" <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))["options"]
want = {"duration_s": 0.5, "fps": 20.0, "max_el_deg": 70.0, "jitter_min_hz": 1.0, "bit_depth": "8", "seed": 1,
        "turret_noise_deg": 0.003, "range_noise_mm": 0.35}
bad = {k: (o.get(k), v) for k, v in want.items() if o.get(k) != v}
if bad or o["trajectory"]["kind"] != "default" or o["camera_preset"] != "small":
    sys.exit("report options differ: %s" % bad)
PY
echo ok
