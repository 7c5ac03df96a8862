#!/usr/bin/env bash
# CLI test rk_capture_file_size_limit: registered, and described, in tests/cli/rk_capture.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_capture/lib.sh"
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
