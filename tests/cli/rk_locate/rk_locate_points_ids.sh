#!/usr/bin/env bash
# CLI test rk_locate_points_ids: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$d/out_ids; rm -rf "$o"; mkdir -p "$o"
# The beacon track as a points track of two ids: p1 the same pixels, p2 ten pixels to the right.
python3 - "$d/track.csv" "$o/points.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["frame", "t_s", "id", "x_px", "y_px", "status", "sigma_x_px", "sigma_y_px", "score"])
    for r in rows:
        for pid, dx in (("p1", 0.0), ("p2", 10.0)):
            x = r["x_px"] and repr(float(r["x_px"]) + dx)
            sx, sy = r.get("sigma_x_px", ""), r.get("sigma_y_px", "")
            w.writerow([r["frame"], r["t_s"], pid, x, r["y_px"], r.get("status", "ok"), sx, sy, "0.9" if x else ""])
PY
rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" \
  -o "$o/plain.csv" --quiet
rk-locate --track "$o/points.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" \
  -o "$o/ids.csv" --report "$o/ids.json" --quiet
head -1 "$o/ids.csv" | grep -q '^frame,t_s,id,az_deg,el_deg,'
test "$(grep -c '' "$o/ids.csv")" = $(( 2 * ($(grep -c '' "$o/plain.csv") - 1) + 1 ))
# p1's rows are the beacon track's rows, value for value; p2's azimuths differ; ids alternate within a frame.
grep ',p1,' "$o/ids.csv" | sed 's/,p1,/,/' > "$o/p1.csv"
tail -n +2 "$o/plain.csv" | cmp - "$o/p1.csv"
test "$(sed -n 2p "$o/ids.csv" | cut -d, -f3)" = p1
test "$(sed -n 3p "$o/ids.csv" | cut -d, -f3)" = p2
! grep ',p2,' "$o/ids.csv" | sed 's/,p2,/,/' | cmp -s - "$o/p1.csv"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); sys.exit(sum(r['rows_by_status'].values()) != 48)" "$o/ids.json"
echo ok
