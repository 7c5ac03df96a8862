#!/usr/bin/env bash
# CLI test rk_capture_status_line: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_capture/lib.sh"
command -v script > /dev/null || { echo "script(1) not installed: skipped"; exit 0; }
d=$data/capture_status; rm -rf "$d"; mkdir -p "$d"; cd "$d"
rk-sim device dimetix --link "$d/dls" --rate-hz 5 --duration 20 > /dev/null &
dls=$!
rk-sim device ptu --link "$d/ptu" --duration 20 > /dev/null &
ptu=$!
trap 'kill $dls $ptu 2>/dev/null || true' EXIT
wait_links "$d/dls" "$d/ptu"
cat > station.json <<EOF
{"cameras": [{"name": "az", "source": "synthetic:160x120", "fps": 20}],
 "rangefinder": {"port": "dls", "baud": 115200, "mode": "tracking", "rate_hz": 5},
 "turret": {"port": "ptu", "baud": 115200, "rate_hz": 50}}
EOF
cap=$(command -v rk-capture)
script -qfec "$cap --config station.json --out tty --duration 2.5" tty.log > /dev/null
grep -aq $'\r''rk-capture [0-9.]* s | az [0-9]* fr [0-9]* drop' tty.log || { echo "no status line"; cat -v tty.log; exit 1; }
grep -aq 'range [0-9.]* Hz | turret [0-9.]* Hz az [0-9.-]* el [0-9.-]*' tty.log || { echo "status line lacks range/turret"; cat -v tty.log; exit 1; }
rk-capture --config station.json --out notty --duration 1.5 2> notty.err
if grep -aq $'\r' notty.err; then echo "status line written to a non-terminal"; cat -v notty.err; exit 1; fi
echo ok
