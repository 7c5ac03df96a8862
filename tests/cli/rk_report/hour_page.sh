#!/usr/bin/env bash
# The report page of a 1-hour, two-station trial at 20 Hz (issue 34's size and first-paint target): used by the
# CLI test rk_report_hour_page and by bench/report_page_bench.sh.
#
#   hour_page.sh DIR [DURATION_S]
#
# Makes DIR/out/ as rk-run would for such a trial, from the tools' own outputs: rk-sim multistation's located
# targets (station 1 at 20 Hz with a rangefinder, station 2 at 25 Hz: 72 000 and 90 000 rows in an hour; a
# climbing turn), rk-intersect's trajectory of them with its report, and an rk-run report.json naming these
# products and the intersect step's tool report as rk-run writes them (the two locate steps and the intersect
# step; no video, so no image track). Then rk-report makes DIR/out/report.html. Prints the page's size and the
# time rk-report took.
set -eu
dir=$1 duration=${2:-3600}
rm -rf "$dir"; mkdir -p "$dir"
rk-sim multistation --out "$dir/sim" --stations 2 --duration "$duration" --rate 20 --range-stations 1 --path turn \
  --seed 3 --quiet
out=$dir/out
mkdir -p "$out/s1/az" "$out/s2/az" "$out/trajectory"
cp "$dir/sim/s1/located.csv" "$out/s1/az/located.csv"
cp "$dir/sim/s2/located.csv" "$out/s2/az/located.csv"
rk-intersect --stations "$dir/sim/stations.json" -o "$out/trajectory/trajectory.csv" \
  --report "$dir/intersect.json" --quiet
python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
stations = json.load(open(d + "/sim/stations.json"))
intersect = json.load(open(d + "/intersect.json"))
def step(unit, kind, tool, path, report=None):
    s = {"id": unit + "/" + kind, "unit": unit, "kind": kind, "tool": tool, "status": "ok",
         "outputs": [{"path": path}], "time": {"wall_s": 0}}
    if report is not None:
        s["tool_report"] = report
    return s
rep = {"tool": "rk-run", "version": "hour_page.sh", "result": "complete",
       "trial": {"name": "hour", "epoch_utc": "2026-11-29T08:00:00Z"},
       "manifest": {"name": "hour", "origin": stations["origin"],
                    "stations": {s["name"]: {"station": {k: s[k] for k in ("lat_deg", "lon_deg", "h_m")},
                                             "cameras": {"az": {"role": "beacon"}}} for s in stations["stations"]}},
       "steps": [step("s1/az", "locate", "rk-locate", "s1/az/located.csv"),
                 step("s2/az", "locate", "rk-locate", "s2/az/located.csv"),
                 step("trajectory", "intersect", "rk-intersect", "trajectory/trajectory.csv", intersect)],
       "counts": {"run": 3, "skipped": 0, "warnings": 0}}
json.dump(rep, open(d + "/out/report.json", "w"), indent=1)
PY
start=$(date +%s.%N)
rk-report "$out" --quiet
end=$(date +%s.%N)
python3 -c "import os,sys; print('page %.1f MB, rk-report %.2f s' % (os.path.getsize(sys.argv[1]) / 1e6, float(sys.argv[3]) - float(sys.argv[2])))" \
  "$out/report.html" "$start" "$end"
