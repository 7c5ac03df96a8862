#!/usr/bin/env bash
# CLI test rk_run_multistation: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/multi; rm -rf "$d"; mkdir -p "$d"
t=$d/ms
# Three rendered stations (5 km baseline, 350 m and 900 m above station 1), a crossing at 3 km, 3 s at 10 Hz
# (stations 2 and 3 at 12.5 and 8 Hz), station 1 with a rangefinder.
rk-sim multistation --out "$t" --stations 3 --duration 3 --rate 10 --path crossing --baseline 5 \
  --range-stations 1 --video mkv --seed 5 --quiet
json "$t/trial.json" 'sorted(d["stations"])' | grep -q "\['s1', 's2', 's3'\]"
rk-run "$t" --no-plots > "$d/run.out"; cat "$d/run.out"
for s in s1/az/extract-beacon s1/az/locate s2/az/locate s3/az/locate trajectory/intersect; do
  grep -Eq "^$s +ok" "$d/run.out" || { echo "step $s did not run ok"; exit 1; }
done
check_out --no-temporaries "$t"
# One report: the intersection's quality figures and the stations.json rk-run wrote (each station's position).
json "$t/out/report.json" '[s["status"] for s in d["steps"] if s["id"]=="trajectory/intersect"][0]' | grep -qx ok
json "$t/out/trajectory/stations.json" 'len(d["stations"])' | grep -qx 3
# The trajectory against truth. Tolerance: each line of sight carries the turret log's 0.003 deg encoder steps
# (±26 µrad) and 5" servo jitter (24 µrad RMS), ≈ 0.25 m across at 5–6 km; the crossing angles (≥ 30°) at most
# triple that: 2 m per axis at every ok row. At least 90 % of the rows ok (the stations' first and last frames
# lack a second line of sight within one frame interval).
python3 - "$t/out/trajectory/trajectory.csv" "$t/truth.csv" <<'PY'
import csv, sys, bisect
TOL_M = 2.0          # see above
MIN_OK_FRACTION = 0.9
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
truth = list(csv.DictReader(l for l in open(sys.argv[2]) if not l.startswith("#")))
tt = [float(r["t_s"]) for r in truth]
ok = [r for r in rows if r["status"] == "ok"]
assert len(ok) >= MIN_OK_FRACTION * len(rows), (len(ok), len(rows))
assert "ve_mps" in rows[0], "the manifest's steps ask for --smooth"
worst = 0.0
for r in ok:
    t = float(r["t_s"]); i = min(max(bisect.bisect_left(tt, t), 1), len(tt) - 1)
    a, b = truth[i - 1], truth[i]; w = (t - tt[i - 1]) / (tt[i] - tt[i - 1])
    for c in ("e_m", "n_m", "u_m"):
        ref = float(a[c]) + w * (float(b[c]) - float(a[c]))   # the crossing is straight and level: exact
        worst = max(worst, abs(float(r[c]) - ref))
print("rows", len(rows), "ok", len(ok), "worst axis error m", round(worst, 3))
assert worst <= TOL_M, worst
PY
rk-run "$t" --no-plots | grep -q 'trajectory/intersect *skipped'
# Issue 34: the trajectory for earth viewers beside the page, out/trajectory.kml and out/trajectory.czml (rk-export
# with the manifest's epoch and name); every coordinate equals the trajectory's WGS-84 columns to 1e-7 deg, the CZML
# packets are as its specification describes; the KML validates against the OGC schema where xmllint and the schema are.
for s in trajectory/export-kml trajectory/export-czml; do
  grep -Eq "^$s +ok" "$d/run.out" || { echo "step $s did not run ok"; exit 1; }
done
python3 "$src/tests/cli/rk_export/check_export.py" "$t/out/trajectory/trajectory.csv" --kml "$t/out/trajectory.kml" \
  --czml "$t/out/trajectory.czml" --epoch "$(json "$t/trial.json" 'd["epoch_utc"]')"
json "$t/out/trajectory.czml" 'd[0]["name"]' | grep -qx ms
schema=${RK_KML_SCHEMA:-$src/build-cache/kml-schema/usr/share/pytrainer/schemas/ogckml22.xsd}
if command -v xmllint >/dev/null && [ -r "$schema" ]; then xmllint --noout --nonet --schema "$schema" "$t/out/trajectory.kml"; fi
# The report page draws the trajectory and the stations from the tools' WGS-84 columns and the manifest's
# positions (issue 28: the page converts no coordinates): a plan view in longitude and latitude with the
# three stations named, and the stations' table without converted ENU columns.
rk-report "$t/out" -o "$d/page.html" -q
python3 - "$d/page.html" <<'PY'
import re, sys
page = open(sys.argv[1]).read()
plan = [s for s in re.findall(r"<svg.*?</svg>", page, re.S) if ">lon_deg<" in s and ">lat_deg<" in s]
assert plan, "no longitude/latitude plan view"
assert any(all(">%s<" % n in svg for n in ("s1", "s2", "s3")) for svg in plan), "stations not marked in the plan view"
assert "trajectory and stations (WGS-84)" in page
stations = page[page.index('id="station"'):]
assert "<th>lat_deg</th>" in stations and "<th>e_m</th>" not in stations.split("</table>")[0]
PY

# Station clocks (issue 33): the same trial with s2's clock 20 ms and s3's -15 ms off, and the manifest's
# "steps": {"intersect": {"estimate-time-offsets": true}}: rk-run passes the flag, the intersection's report has
# time_offsets within 3 sigma of the truth, and the page shows them.
c=$d/clocks
rk-sim multistation --out "$c" --stations 3 --duration 3 --rate 10 --path crossing --baseline 5 \
  --range-stations 1 --video mkv --seed 5 --time-offsets s2:0.02,s3:-0.015 --quiet
python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); m['steps']['intersect']['estimate-time-offsets']=True; json.dump(m,open(p,'w'),indent=1)" "$c/trial.json"
rk-run "$c" --no-plots > "$d/clocks.out"
grep -Eq "^trajectory/intersect +ok" "$d/clocks.out"
python3 - "$c/out/report.json" <<'PY'
import json, sys
st = [s for s in json.load(open(sys.argv[1]))["steps"] if s["id"] == "trajectory/intersect"][0]
t = st["tool_report"]["time_offsets"]
assert t["s1.az"]["reference"], t
for name, truth in (("s2.az", 0.02), ("s3.az", -0.015)):
    assert abs(t[name]["offset_s"] - truth) < 3 * t[name]["sigma_s"], (name, t[name])
print({k: (round(v["offset_s"], 5), round(v["sigma_s"], 5)) for k, v in t.items()})
PY
rk-report "$c/out" -o "$d/clocks.html" -q
grep -q 'station clock offsets (rk-intersect --estimate-time-offsets)' "$d/clocks.html"
grep -q '<td>s2.az</td><td class="num">' "$d/clocks.html"

# Malformed multi-station manifests: exit 3 at trial.json:LINE:COL, nothing written.
bad() {  # bad NAME PYTHON-EDIT: a copy of the trial with its manifest edited (m = the manifest)
  rm -rf "$d/$1"; cp -r "$t" "$d/$1"; rm -rf "$d/$1/out" "$d/$1"/last-run.json "$d/$1"/rk-run.log
  python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); $2; json.dump(m,open(p,'w'),indent=1)" "$d/$1/trial.json"
}
bad one 'm["stations"]={"s1": m["stations"]["s1"]}'
"$expect" 3 "$d/one/out" "trial.json:[0-9]+:[0-9]+: stations: a multi-station trial needs at least two stations" -- rk-run "$d/one"
bad nopos 'del m["stations"]["s2"]["station"]'
"$expect" 3 "$d/nopos/out" "trial.json:[0-9]+:[0-9]+: stations.s2: missing field 'station'" -- rk-run "$d/nopos"
bad role 'm["stations"]["s3"]["cameras"]["az"]["role"]="beakon"'
line=$(grep -n beakon "$d/role/trial.json" | cut -d: -f1)
"$expect" 3 "$d/role/out" "trial.json:$line:[0-9]+: stations.s3.cameras.az.role: 'beakon' is not one of" -- rk-run "$d/role"
bad both 'm["cameras"]=m["stations"]["s1"]["cameras"]'
"$expect" 3 "$d/both/out" "trial.json:[0-9]+:[0-9]+: cameras: a manifest with 'stations' gives 'cameras' per station" -- rk-run "$d/both"
bad name 'm["stations"]["trajectory"]=m["stations"].pop("s3")'
"$expect" 3 "$d/name/out" "trial.json:[0-9]+:[0-9]+: stations.trajectory: station name 'trajectory'" -- rk-run "$d/name"
bad lat 'm["stations"]["s2"]["station"]["lat_deg"]=95'
"$expect" 3 "$d/lat/out" "trial.json:[0-9]+:[0-9]+: stations.s2.station.lat_deg: latitude must be in" -- rk-run "$d/lat"
bad unit 'm["steps"]["s9/az/locate"]={}'
"$expect" 3 "$d/unit/out" "trial.json:[0-9]+:[0-9]+: steps.s9/az/locate: no camera 'STATION/CAMERA' named 's9/az'" -- rk-run "$d/unit"
bad noturret 'm["stations"]["s2"]["turret"]=None; m["stations"]["s3"]["turret"]=None'
"$expect" 3 "$d/noturret/out" "trial.json:[0-9]+:[0-9]+: stations.s2.cameras.az.role: a beacon camera asks for s2/az/locate, which cannot run" -- rk-run "$d/noturret"
bad missing 'm["stations"]["s2"]["turret"]="s2/no_such.csv"'
"$expect" 4 "$d/missing/out" 's2/no_such.csv' -- rk-run "$d/missing"
# The intersection needs several stations: a single-station manifest may not ask for it.
s=$d/single; fresh "$s"; python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); m['steps']={'intersect': {'smooth': True}}; json.dump(m,open(p,'w'),indent=1)" "$s/trial.json"
"$expect" 3 "$s/out" "trial.json:[0-9]+:[0-9]+: steps.intersect: step 'intersect' needs several stations" -- rk-run "$s"
echo ok
