# CLI tests of rk-capture and rk-sim device (SPEC.md §4, §6; docs/rk-capture.md).
# The full test records emulated devices (rk-sim device dimetix|ptu, with injected faults) and a
# replayed video (the sim_small fixture, looped) for 11.5 s, kills rk-capture with SIGKILL, runs
# `rk-capture recover` and checks every record against the emulators' truth logs and every frame
# against the source video (tests/cli/capture_check.py).
# Shell scripts get $1 = RK_CLI_DATA, $2 = expect.sh, $3 = the source folder; rk-* are on PATH.
# wait_links PATH...: waits until the emulators' links exist (they are made once the pty is up).
set(RK_CAPTURE_PRELUDE [==[
wait_links() { for i in $(seq 1 100); do ok=1; for l in "$@"; do [ -e "$l" ] || ok=0; done; [ $ok = 1 ] && return 0; sleep 0.05; done; echo "emulator did not start"; return 1; }
]==])
function(rk_capture_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
       "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; src=$3\n${RK_CAPTURE_PRELUDE}${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT}
              ${RK_SOURCE_DIR})
endfunction()


rk_capture_script(rk_capture_kill9_recover [==[
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
]==] REQUIRES sim_small)

# SIGINT: clean stop, exit 0, manifest complete, nothing to repair; the station's model copied in.
rk_capture_script(rk_capture_sigint_clean [==[
d=$data/capture_sigint; rm -rf "$d"; mkdir -p "$d"; cd "$d"
rk-sim device dimetix --link "$d/dls" --duration 20 > /dev/null &
dls=$!
trap 'kill $dls 2>/dev/null || true' EXIT
wait_links "$d/dls"
printf '%s\n' '{"width_px": 320, "height_px": 240, "pixel_size_mm": [0.005, 0.005], "focal_length_mm": 25,' \
  '"principal_point_px": [159.5, 119.5]}' > cam.json
cat > station.json <<EOF
{"cameras": [{"name": "att", "source": "synthetic:320x240", "fps": 25, "model": "cam.json",
              "role": "features", "format": "pgm"}],
 "rangefinder": {"port": "dls", "baud": 115200, "mode": "single", "rate_hz": 5}}
EOF
rk-capture --config station.json --out trial --report report.json 2> capture.err &
cap=$!
sleep 2.5
kill -INT $cap
wait $cap
grep -q 'recorded .* s into trial (signal)' capture.err
python3 - <<'PY'
import json
m = json.load(open("trial/trial.json"))
assert m["capture"]["state"] == "complete" and m["capture"]["stop_reason"] == "signal", m["capture"]["state"]
assert m["cameras"]["att"]["video"] == ["att/seg_000/%06d.pgm"], m["cameras"]["att"]
assert m["cameras"]["att"]["model"] == "att/camera.json" and m["cameras"]["att"]["role"] == "features"
assert m["range"] == "range.csv" and m["turret"] is None and m["theodolite"] is None and m["radar"] is None
r = json.load(open("report.json"))
assert r["tool"] == "rk-capture" and r["summary"]["range"]["rows"] >= 8, r["summary"]
PY
cmp cam.json trial/att/camera.json
rk-capture recover trial 2> rec.err
grep -q ' 0 repair(s)' rec.err
echo ok
]==])

# A file-size limit (ulimit -f, RLIMIT_FSIZE) hits the video in the middle of frames: each frame is
# written whole or not at all, the recording goes on in new segments, the other files stay
# readable, the exit status is 4, and recover finds the trial readable.
rk_capture_script(rk_capture_file_size_limit [==[
d=$data/capture_fsize; rm -rf "$d"; mkdir -p "$d"; cd "$d"
cat > station.json <<EOF
{"cameras": [{"name": "az", "source": "synthetic:640x512", "fps": 20}], "segment_s": 1}
EOF
set +e
( ulimit -f 3000; exec rk-capture --config station.json --out trial --duration 2 --quiet ) 2> capture.err
rc=$?
set -e
cat capture.err
test $rc = 4
grep -q 'could not be written' capture.err
grep -q 'File too large' trial/events.log
rk-capture recover trial 2> rec.err
python3 - <<'PY'
import csv, json, os
m = json.load(open("trial/trial.json"))
rows = [r for r in csv.DictReader(l for l in open("trial/az/frames.csv") if not l.startswith("#"))]
frame_bytes = 6 + 640 * 512
n = 0
for seg in m["cameras"]["az"]["video"]:
    p = os.path.join("trial", seg)
    header = open(p, "rb").readline()
    size = os.path.getsize(p) - len(header)
    assert size % frame_bytes == 0, (seg, size)  # whole frames only
    n += size // frame_bytes
assert n == len(rows) and n >= 20, (n, len(rows))
assert len(m["cameras"]["az"]["video"]) >= 3, m["cameras"]["az"]["video"]
assert m["capture"]["streams"]["cameras"]["az"]["write_failed"] > 0
PY
echo ok
]==])

# Bad usage → 2; bad data → 3 with the file (and line:col for JSON syntax); missing device → 4.
# Nothing is left behind and nothing the user gave is touched.
rk_capture_script(rk_capture_errors [==[
d=$data/capture_err; rm -rf "$d"; mkdir -p "$d"; cd "$d"
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48"}]}' > ok.json
"$expect" 2 out1 'config is required' -- rk-capture --out out1
"$expect" 2 - 'unknown|extra|not expected|The following' -- rk-capture --config ok.json --out out1 --bogus
"$expect" 4 out1 'missing.json' -- rk-capture --config missing.json --out out1
printf '{"cameras": [\n  {"name": "az",,}\n]}\n' > syntax.json
"$expect" 3 out1 'syntax.json:2:' -- rk-capture --config syntax.json --out out1
echo '{"rangefinder": {"port": "/dev/null", "parity": "mark"}}' > parity.json
"$expect" 3 out1 "parity.json: rangefinder: 'parity'" -- rk-capture --config parity.json --out out1
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48", "fps": -1}]}' > fps.json
"$expect" 3 out1 "fps" -- rk-capture --config fps.json --out out1 --quiet
echo '{"cameras": [{"name": "az", "source": "synthetic:64x48"}], "rangefinder": {"port": "nothere"}}' > port.json
"$expect" 4 out1 'nothere' -- rk-capture --config port.json --out out1 --quiet
mkdir keep; echo precious > keep/file
"$expect" 2 - 'not empty' -- rk-capture --config ok.json --out keep --quiet
test "$(cat keep/file)" = precious && test "$(ls keep)" = file
"$expect" 2 - 'duration' -- rk-capture --config ok.json --out out1 --duration -1 --quiet
test ! -e out1
# recover: not a trial (4), a trial with unreadable data (3), usage (2)
mkdir empty
"$expect" 4 - 'trial.json' -- rk-capture recover empty
"$expect" 2 - 'recover takes' -- rk-capture --config ok.json recover empty
rk-capture --config ok.json --out t --duration 0.6 --quiet
printf 'oops\n' >> t/az/frames.csv && printf '9,1.0,1,1,9,0\n' >> t/az/frames.csv
"$expect" 3 - 'frames.csv:' -- rk-capture recover t
# rk-sim device: bad fault, missing kind
"$expect" 2 - 'fault' -- rk-sim device dimetix --fault bogus:1:1 --duration 1
"$expect" 2 - '' -- rk-sim device
echo ok
]==])

# A really full disk (ENOSPC), where the machine allows it: tests/cli/capture_disk_full.sh mounts a
# 12 MB tmpfs in a private mount namespace (needs CAP_SYS_ADMIN; the test is skipped otherwise).
rk_cli_test(rk_capture_disk_full COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/capture_disk_full.sh ${RK_CLI_DATA})
set_tests_properties(rk_capture_disk_full PROPERTIES SKIP_RETURN_CODE 77)

# The live status line: on a terminal (a pty from script(1)), rewritten in place with frames, drops, range
# rate and turret angles; not printed when stderr is not a terminal.
rk_capture_script(rk_capture_status_line [==[
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
]==])
