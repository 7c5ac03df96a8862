#!/usr/bin/env bash
# CLI test import_cli_sources: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
i=$data/import
check() { /usr/bin/python3 - "$@"; }
# MRAW (the .cihx path works as well as the .mraw): frame / 20 Hz, nominal.
rk-import frames --video "$i/beacon.cihx" -o "$i/beacon_frames.csv"
check "$i/beacon_frames.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert len(rows) == 60 and all(abs(float(r["t_s"]) - int(r["frame"]) / 20) < 1e-9 and r["time_source"] == "nominal" for r in rows)
PY
# CINE time block against the epoch 10 s before its first stamp (2023-11-14T22:13:20Z): gap and step back said.
rk-import frames --video "$i/gaps.cine" --epoch-utc 2023-11-14T22:13:10Z -o "$i/gaps.csv" --report "$i/gaps.json" 2> "$i/gaps.err"
cat "$i/gaps.err"
grep -q "warning: frame 3: gap of 0.003000000 s" "$i/gaps.err"
grep -q "warning: frame 4: time goes back by 0.001000000 s" "$i/gaps.err"
check "$i/gaps.csv" "$i/gaps.json" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert [int(r["frame"]) for r in rows] == list(range(6))
want = [10.000, 10.001, 10.002, 10.005, 10.004, 10.005]
assert all(abs(float(r["t_s"]) - w) < 2e-9 for r, w in zip(rows, want)), rows
assert all(r["time_source"] == "irig" for r in rows)
rep = json.load(open(sys.argv[2]))
assert sorted(w["code"] for w in rep["warnings"]) == ["frame_gap", "time_backwards"], rep["warnings"]
assert rep["frame_times"]["relative_to"] == "epoch" and rep["frame_times"]["gaps"] == 1
PY
# Without --epoch-utc: from the first frame, said.
rk-import frames --video "$i/gaps.cine" -o - 2> "$i/gaps_noepoch.err" | grep -q "^5,0.005000000,irig"
grep -q "no --epoch-utc" "$i/gaps_noepoch.err"
# rk-capture's segments: host times from its frames.csv, segment by segment.
rk-import frames --video "$i/cam/seg_000.y4m" --video "$i/cam/seg_001.y4m" -o "$i/cam_frames.csv"
check "$i/cam_frames.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert [float(r["t_s"]) for r in rows] == [100.0, 100.05, 100.1, 100.15, 100.22, 100.25], rows
assert all(r["time_source"] == "host" for r in rows)
PY
# The MKV: its container's presentation times (Matroska, 20 fps).
rk-import frames --video "$data/extract/beacon.mkv" -o "$i/mkv_frames.csv"
check "$i/mkv_frames.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
assert len(rows) == 60 and all(r["time_source"] == "container" and abs(float(r["t_s"]) - int(r["frame"]) / 20) < 1e-3 for r in rows)
PY
# An image sequence with --fps: nominal.
rk-import frames --video "$data/extract/seq/%06d.png" --fps 20 -o - | awk -F, 'NR>1 && !/^#/{n++; if ($3 != "nominal") exit 1} END{exit n != 60}'
echo PASS
