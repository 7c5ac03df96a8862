#!/usr/bin/env bash
# CLI test rk_intersect_data: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/intersect; rm -rf "$d"; mkdir -p "$d"
rk-sim multistation --out "$d/trial" --stations 3 --duration 5 --range-stations 1 --seed 3 --quiet
t=$d/trial
# Station s2 shifted 100 s later: its times never overlap s3's (neither has a range).
mkdir -p "$d/late"
awk -F, 'BEGIN{OFS=","} NR==1{print; next} {$1=sprintf("%.9f",$1+100); print}' "$t/s2/located.csv" >"$d/late/s2.csv"
cp "$t/s3/located.csv" "$d/late/s3.csv"
python3 - "$t/stations.json" "$d" <<'PY'
import json, sys
st = json.load(open(sys.argv[1])); d = sys.argv[2]
t = d + "/trial/"
for s in st["stations"]:
    s["located"] = t + s["located"]
def dump(name, obj, text=None):
    with open(d + "/" + name, "w") as f:
        f.write(text if text is not None else json.dumps(obj, indent=2) + "\n")
late = json.loads(json.dumps(st)); late["stations"] = late["stations"][1:3]
late["stations"][0]["located"] = d + "/late/s2.csv"; late["stations"][1]["located"] = d + "/late/s3.csv"
dump("stations_late.json", late)
one = json.loads(json.dumps(st)); one["stations"] = one["stations"][:1]
dump("stations_one.json", one)
missing = json.loads(json.dumps(st)); missing["stations"][1]["located"] = d + "/no_such.csv"
dump("stations_missing.json", missing)
nopos = json.loads(json.dumps(st)); del nopos["stations"][2]["lat_deg"]
dump("stations_nopos.json", nopos)
dump("stations_syntax.json", None, '{"stations": [\n  {"name": "s1",, "lat_deg": 1}\n]}\n')
PY
echo 't_s' >"$d/times.csv"; printf '1.0\n2.0\n3.0\n' >>"$d/times.csv"
# --at times after every station's last row (issue 18: the error says so, not "never overlap").
echo 't_s' >"$d/times_after.csv"; printf '500.0\n501.0\n' >>"$d/times_after.csv"
echo ok
