#!/usr/bin/env bash
# Issue 6 target: range and turret records — no sample lost in a 10-minute emulated run, time stamps
# monotonic. Emulated Dimetix DLS (tracking, 5 Hz) and FLIR PTU (polled at 50 Hz) on pseudo-terminals,
# plus a small synthetic camera, recorded by rk-capture for RK_SECONDS (default 600); every record is
# then checked against the emulators' truth logs (tests/cli/capture_check.py) and the stamping
# latency and sample intervals are summarised.
#   bash bench/capture_long_run.sh [BUILD_DIR] [WORK_DIR]
set -euo pipefail
SRC=$(cd "$(dirname "$0")/.." && pwd)
B=$(cd "${1:-$SRC/build}" && pwd)/apps
W=${2:-/var/tmp/rk-capture-long}
SECONDS_RUN=${RK_SECONDS:-600}
rm -rf "$W"; mkdir -p "$W"; cd "$W"
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$B/rk-sim" device dimetix --link "$W/dls" --truth dls_truth.csv --rate-hz 5 > /dev/null &
dls=$!
"$B/rk-sim" device ptu --link "$W/ptu" --truth ptu_truth.csv > /dev/null &
ptu=$!
trap 'kill $dls $ptu 2>/dev/null || true' EXIT
for i in $(seq 1 100); do [ -e "$W/dls" ] && [ -e "$W/ptu" ] && break; sleep 0.05; done
cat > station.json <<JSON
{"name": "long-run",
 "cameras": [{"name": "az", "source": "synthetic:320x256", "fps": 20}],
 "rangefinder": {"port": "dls", "baud": 115200, "mode": "tracking", "rate_hz": 5},
 "turret": {"port": "ptu", "baud": 115200, "rate_hz": 50, "timeout_s": 0.2},
 "segment_s": 60}
JSON
/usr/bin/time -f "rk-capture: %e s wall, %U s user, %S s sys, %M kB max RSS" \
  "$B/rk-capture" --config station.json --out trial --duration "$SECONDS_RUN" --quiet --report report.json
kill -TERM $dls $ptu; wait $dls $ptu || true
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 "$SRC/tests/cli/capture_check.py" trial --dls-truth dls_truth.csv --ptu-truth ptu_truth.csv --state complete
python3 - <<'PY'
import csv, json
def rows(p):
    return [r for r in csv.DictReader(l for l in open(p) if not l.startswith("#"))]
def truth(p):
    out = []
    for line in list(open(p))[1:]:
        m, e, d = line.rstrip("\n").split(",", 2)
        out.append((float(m), e, d))
    return out
rep = json.load(open("report.json"))["summary"]
rng, tur = rows("trial/range.csv"), rows("trial/turret.csv")
sent = [m for m, e, d in truth("dls_truth.csv") if e == "sent" and (d.startswith("g0h") or d.startswith("g0@E"))]
lat = sorted(float(r["host_mono_s"]) - s for r, s in zip(rng, sent))
def intervals(rs):
    t = [float(r["t_s"]) for r in rs]
    d = sorted(b - a for a, b in zip(t, t[1:]))
    return d[0], d[len(d) // 2], d[-1]
print("range:  %d rows, %d measurements sent, latency median %.3f ms, max %.3f ms; interval min/median/max %.4f/%.4f/%.4f s"
      % ((len(rng), len(sent), lat[len(lat) // 2] * 1e3, lat[-1] * 1e3) + intervals(rng)))
print("turret: %d rows; interval min/median/max %.4f/%.4f/%.4f s; late polls %d"
      % ((len(tur),) + intervals(tur) + (rep["turret"]["late_polls"],)))
print("camera: %d frames written, %d dropped" % (rep["cameras"]["az"]["frames_written"],
      rep["cameras"]["az"]["dropped_queue_full"] + rep["cameras"]["az"]["dropped_disk_low"]))
print("gaps: %d, write failures: %d, stamping threads: %s" % (rep["gaps"], rep["write_failures"],
      json.load(open("trial/trial.json"))["capture"]["stamping_threads"]))
PY
