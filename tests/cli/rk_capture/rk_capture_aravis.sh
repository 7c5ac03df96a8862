#!/usr/bin/env bash
# CLI test rk_capture_aravis: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
if ! command -v arv-fake-gv-camera-0.8 >/dev/null || ! command -v ip >/dev/null; then
  echo "SKIP: Aravis' software camera (aravis-tools) or ip (iproute2) is not installed (scripts/setup.sh --gige)"
  exit 77
fi
if ! unshare -n true 2>/dev/null; then
  echo "SKIP: no private network namespace here (unshare -n needs CAP_SYS_ADMIN)"
  exit 77
fi
d=$data/capture_aravis; rm -rf "$d"; mkdir -p "$d"
# A station with one GigE Vision camera: a size, rate and exposure other than the fake camera's defaults
# (512x512, 25 fps, 1000 us), set in the file's order and read back.
cat >"$d/station.json" <<'JSON'
{"cameras": [{"name": "gige", "source": "aravis:Aravis-Fake-RK1", "fps": 20,
              "features": {"Width": 320, "Height": 240, "AcquisitionFrameRate": 20, "ExposureTimeAbs": 2500}}],
 "segment_s": 2}
JSON
cat >"$d/missing.json" <<'JSON'
{"cameras": [{"name": "gige", "source": "aravis:Aravis-Fake-NOSUCH", "fps": 20}]}
JSON
# Everything inside a private network namespace: the fake camera answers on its loopback only, never on a
# real network.
cat >"$d/run.sh" <<'SH'
set -eu
d=$1 expect=$2
ip link set lo up
arv-fake-gv-camera-0.8 -i 127.0.0.1 -s RK1 >"$d/fake.log" 2>&1 &
fake=$!
trap 'kill $fake 2>/dev/null || true' EXIT
for _ in $(seq 50); do rk-capture --list-cameras | grep -q '^Aravis-Fake-RK1,' && break; sleep 0.1; done
rk-capture --list-cameras >"$d/list.csv"
rk-capture --config "$d/station.json" --out "$d/trial" --duration 6 --report "$d/report.json" --quiet
# The camera paused (SIGSTOP) for 2 s and resumed, then killed and started again 3 s later: two gaps, one
# reconnect with the features set again, exit 0.
rk-capture --config "$d/station.json" --out "$d/trial2" --duration 14 --report "$d/report2.json" --quiet &
cap=$!
sleep 3; kill -STOP $fake; sleep 2; kill -CONT $fake
sleep 2; kill $fake; wait $fake 2>/dev/null || true; sleep 3
arv-fake-gv-camera-0.8 -i 127.0.0.1 -s RK1 >"$d/fake2.log" 2>&1 &
fake=$!
wait $cap
# Packet loss (the software camera's own option: 5 GVSP packets in 1000 lost; no resends): incomplete frames.
# One software camera at a time: both would listen on the GVCP port of the one address.
kill $fake; wait $fake 2>/dev/null || true
arv-fake-gv-camera-0.8 -i 127.0.0.1 -s RK2 -r 5 >"$d/fake3.log" 2>&1 &
lossy=$!
# (and IEEE 1588 asked for, which the software camera does not have: said, not silently ignored; and 16-bit
# frames, Mono16)
sed -e 's/Aravis-Fake-RK1/Aravis-Fake-RK2/' -e 's/"fps": 20,/"fps": 20, "ptp": true,/' \
  -e 's/"ExposureTimeAbs": 2500}/"ExposureTimeAbs": 2500, "PixelFormat": "Mono16"}/' "$d/station.json" >"$d/lossy.json"
for _ in $(seq 50); do rk-capture --list-cameras | grep -q '^Aravis-Fake-RK2,' && break; sleep 0.1; done
rk-capture --config "$d/lossy.json" --out "$d/trial3" --duration 5 --report "$d/report3.json" --quiet
kill $lossy
# A camera that does not answer: exit 4, one line naming it, no trial left behind.
"$expect" 4 "$d/trial_missing" 'Aravis-Fake-NOSUCH' -- rk-capture --config "$d/missing.json" --out "$d/trial_missing" --duration 2 -q
SH
unshare -n bash "$d/run.sh" "$d" "$expect"
grep -q '^id,model,serial,address$' "$d/list.csv"
grep -q '^Aravis-Fake-RK1,Fake,RK1,127.0.0.1$' "$d/list.csv"
python3 - "$d" <<'PY'
import csv, json, sys
d = sys.argv[1]
rows = list(csv.DictReader(l for l in open(d + "/trial/gige/frames.csv") if not l.startswith("#")))
RATE, DURATION = 20.0, 6.0
# Frame count = duration × rate within one frame (the first frame waits for the acquisition to start).
assert abs(len(rows) - RATE * DURATION) <= 1 + 1, len(rows)
cam = [float(r["camera_ts_s"]) for r in rows]
dt = [b - a for a, b in zip(cam, cam[1:])]
assert all(x > 0 for x in dt), "camera stamps not strictly increasing"
mean = sum(dt) / len(dt)
assert abs(mean - 1 / RATE) < 0.01 / RATE, mean          # the configured period within 1 %
assert all(len(r["camera_ts_s"].split(".")[1]) >= 6 for r in rows)
# t_s from the camera's stamp through the clock mapping, said so, strictly increasing, within a few ms of the
# host's arrival (the software camera stamps when it sends: its stamps jitter too).
assert all(r["time_source"] == "camera" for r in rows), set(r["time_source"] for r in rows)
t = [float(r["t_s"]) for r in rows]
assert all(b > a for a, b in zip(t, t[1:]))
host = [float(r["host_mono_s"]) for r in rows]
arrival = [h - host[0] + t[0] for h in host]
assert max(abs(a - b) for a, b in zip(t, arrival)) < 0.005
seq = [int(r["seq"]) for r in rows]
assert seq == list(range(len(rows))), "a frame dropped or duplicated"
c = json.load(open(d + "/report.json"))["summary"]["cameras"]["gige"]
assert c["width"] == 320 and c["height"] == 240, c
assert c["dropped_queue_full"] == 0 and c["source_errors"] == 0, c
s = c["stream"]
assert s["frames_complete"] == len(rows) and s["frames_incomplete"] == 0 and s["frames_never_arrived"] == 0, s
asked = [(f["name"], f["asked"], f["got"]) for f in s["features"]]
assert asked == [("Width", "320", "320"), ("Height", "240", "240"), ("AcquisitionFrameRate", "20", "20"),
                 ("ExposureTimeAbs", "2500", "2500")], asked
clock = s["camera_clock"]
assert clock["frames"] == len(rows) and clock["residual_rms_s"] < 0.02, clock
events = open(d + "/trial/events.log").read()
assert "feature ExposureTimeAbs = 2500" in events
print("frames", len(rows), "period", mean, "clock", clock["drift_ppm"], clock["residual_rms_s"])
# The pause and the restart: two gaps (the pause from the camera's own stamps, the restart from its silence),
# one reopen with the features set again, no frame duplicated (camera stamps strictly increasing), the gaps
# spanning the silences (≥ 1.9 s and ≥ 3 s from the last frame before them).
r2 = json.load(open(d + "/report2.json"))["summary"]
c2 = r2["cameras"]["gige"]
assert r2["gaps"] == 2, r2["gaps"]
assert c2["stream"]["opens"] == 2 and c2["source_errors"] == 1, c2
rows2 = list(csv.DictReader(l for l in open(d + "/trial2/gige/frames.csv") if not l.startswith("#")))
cam2 = [float(r["camera_ts_s"]) for r in rows2]
steps = [b - a for a, b in zip(cam2, cam2[1:])]
assert all(x > 0 for x in steps), "a frame duplicated or out of order"
long = sorted(x for x in steps if x > 0.5)
assert len(long) == 2 and long[0] > 1.9 and long[1] > 3.0, long
ev = open(d + "/trial2/events.log").read()
assert ev.count("feature Width = 320") == 2 and "reopened" in ev, ev
gaps = json.load(open(d + "/trial2/trial.json"))["capture"]["gaps"]
spans = sorted(g["end_s"] - g["start_s"] for g in gaps)
assert spans[0] > 1.9 and spans[1] > 3.0, gaps
# Packet loss: frames with missing packets are counted and never written; frames.csv's seq jumps by the frames
# lost (incomplete or never arrived) before each written one.
c3 = json.load(open(d + "/report3.json"))["summary"]["cameras"]["gige"]
s3 = c3["stream"]
assert s3["frames_incomplete"] > 0, s3
assert c3["bit_depth"] == 16, c3
assert c3["frames_written"] == s3["frames_complete"] == c3["frames_grabbed"], (c3, s3)
rows3 = list(csv.DictReader(l for l in open(d + "/trial3/gige/frames.csv") if not l.startswith("#")))
seq3 = [int(r["seq"]) for r in rows3]
lost = seq3[-1] + 1 - len(rows3)
assert all(b > a for a, b in zip(seq3, seq3[1:]))
assert 0 <= s3["frames_incomplete"] + s3["frames_never_arrived"] - lost <= 3, (lost, s3)
assert "neither PtpEnable nor GevIEEE1588" in s3["ptp"]["error"], s3["ptp"]
assert "IEEE 1588 asked for" in open(d + "/trial3/events.log").read()
print("lossy: written", len(rows3), "incomplete", s3["frames_incomplete"], "never arrived", s3["frames_never_arrived"])
PY
test ! -e "$d/trial_missing"
echo ok
