#!/usr/bin/env bash
# CLI test rk_capture_kill9_recover: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_capture/lib.sh"
d=$data/capture_full; rm -rf "$d"; mkdir -p "$d"; cd "$d"
video=$data/small/az/video.mkv
ffmpeg -v error -nostdin -i "$video" -map 0:v:0 -pix_fmt gray -f framemd5 - > source.md5
# Devices with faults (seconds after the emulator starts): error replies, silence longer than the
# driver's timeout (a gap), garbage, late replies.
rk-sim device dimetix --link "$d/dls" --truth dls_truth.csv --rate-hz 5 --seed 3 \
  --fault error:2.5:1 --fault silence:5:1.6 --fault garbage:8:0.5 --duration 40 > dls.port &
dls=$!
rk-sim device ptu --link "$d/ptu" --truth ptu_truth.csv --seed 4 \
  --fault error:2:0.3 --fault slow:4:0.4:0.3 --fault silence:7:0.5 --fault garbage:9:0.2 --duration 40 > ptu.port &
ptu=$!
trap 'kill $dls $ptu 2>/dev/null || true' EXIT
wait_links "$d/dls" "$d/ptu"
cat > station.json <<EOF
{"name": "kill9",
 "station": {"lat_deg": 39.9, "lon_deg": 116.3, "h_m": 50.0},
 "cameras": [{"name": "az", "source": "file:$video", "loop": true, "fps": 20,
              "model": "$data/small/az/camera.json", "role": "beacon"}],
 "rangefinder": {"port": "dls", "baud": 115200, "parity": "none", "data_bits": 8, "stop_bits": 1,
                 "mode": "tracking", "rate_hz": 5, "timeout_s": 1.0, "reconnect_s": 0.5},
 "turret": {"port": "ptu", "baud": 115200, "rate_hz": 50, "timeout_s": 0.2, "pan_zero_deg": 350.0},
 "segment_s": 4}
EOF
rk-capture --config station.json --out trial --duration 60 --quiet 2> capture.err &
cap=$!
sleep 11.5
# SIGKILL in the middle of the recording; the CLOCK_MONOTONIC time of the kill is the cutoff.
killed=$(python3 -c "import os, signal, time; os.kill($cap, signal.SIGKILL); print('%.6f' % time.monotonic())")
set +e; wait $cap; rc=$?; set -e
test $rc = 137 || { echo "rk-capture exited $rc before the kill"; cat capture.err; exit 1; }
kill -TERM $dls $ptu; wait $dls $ptu || true
python3 -c "import json; m = json.load(open('trial/trial.json')); assert m['capture']['state'] == 'recording', m['capture']['state']"
rk-capture recover trial --report recover.json
python3 -c "import json; r = json.load(open('recover.json'))['summary']; assert r['readable'] and r['state_after'] == 'recovered', r"
# Nothing older than one second before the kill may be lost.
python3 "$src/tests/cli/capture_check.py" trial --dls-truth dls_truth.csv --ptu-truth ptu_truth.csv \
  --source-md5 source.md5 --cutoff "$(python3 -c "print($killed - 1.0)")" --state recovered --min-frames 150 \
  --expect-faults
# rk-extract reads the segments as the manifest lists them, unchanged.
args=$(python3 -c "import json; m = json.load(open('trial/trial.json')); print(' '.join('--video trial/' + v for v in m['cameras']['az']['video']))")
rk-extract beacon $args --frames trial/az/frames.csv -o track.csv --quiet
test "$(grep -vc '^#' track.csv)" = "$(grep -vc '^#' trial/az/frames.csv)"
# A second recover finds nothing to repair.
rk-capture recover trial 2> again.err
grep -q ' 0 repair(s)' again.err
echo ok
