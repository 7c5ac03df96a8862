#!/usr/bin/env bash
# CLI test rk_intersect_offsets: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/intersect_offsets; rm -rf "$d"; mkdir -p "$d"
L() { "$expect" "$@"; }
# A climbing turn seen by three stations whose clocks are 4.3 ms and -11.7 ms off the first's.
rk-sim multistation --out "$d/turn" --path turn --baseline 10 --sigma-angle 2 --duration 20 --seed 5 \
  --time-offsets s2:0.0043,s3:-0.0117 --quiet
rk-intersect --stations "$d/turn/stations.json" -o "$d/est.csv" --estimate-time-offsets --report "$d/est.json" --quiet
rk-intersect --stations "$d/turn/stations.json" -o "$d/none.csv" --report "$d/none.json" --quiet
# The offsets within 3 sigma of the truth, sigma below 0.1 ms, the reference s1 at 0; the residuals with the
# offsets as given much larger than with the estimated ones; no warning; the trajectory with the estimated offsets
# within 5 sigma of the truth on every ok row (its sigma includes the offsets'), and much closer than without.
python3 - "$d" <<'PY'
import csv, json, sys
d = sys.argv[1]
r = json.load(open(d + "/est.json"))
truth = {"s2": 0.0043, "s3": -0.0117}
t = r["time_offsets"]
assert t["s1"]["reference"] and t["s1"]["offset_s"] == 0 and t["s1"]["sigma_s"] == 0, t["s1"]
for s, x in truth.items():
    e = t[s]["offset_s"] - x
    assert abs(e) < 3 * t[s]["sigma_s"], (s, e, t[s])
    assert t[s]["sigma_s"] < 1e-4, t[s]
f = r["time_offset_fit"]
assert f["reference"] == "s1" and f["warnings"] == [], f
assert f["rms_residual_arcsec"]["offsets_as_given"] > 5 * f["rms_residual_arcsec"]["offsets_estimated"], f
assert not [w for w in r["warnings"] if w["code"] == "time_offset_poorly_determined"]
# How far the offsets move the trajectory (the figure that says why they matter): metres here, against a 3-D σ
# of centimetres.
assert f["trajectory_shift_m"]["rms"] > 0.2 and f["trajectory_shift_m"]["max"] >= f["trajectory_shift_m"]["rms"], f
assert "trajectory moved by the offsets" in r["headline"], r["headline"].keys()
tr = {row["t_s"]: row for row in csv.DictReader(open(d + "/turn/truth.csv"))}
def err(path):
    s2, n = 0.0, 0
    for row in csv.DictReader(open(path)):
        if row["status"] != "ok" or row["t_s"] not in tr: continue
        for c in "enu":
            e = float(row[c + "_m"]) - float(tr[row["t_s"]][c + "_m"])
            if path.endswith("est.csv"):
                assert abs(e) < 5 * float(row["sigma_%s_m" % c]) + 1e-3, (row["t_s"], c, e)
            s2 += e * e; n += 1
    return (s2 / n) ** 0.5
e_est, e_none = err(d + "/est.csv"), err(d + "/none.csv")
assert e_none > 3 * e_est, (e_est, e_none)
print("offsets", t["s2"]["offset_s"], t["s3"]["offset_s"], "3-D RMS estimated %.3f m, without %.3f m" % (e_est, e_none))
PY
# A known time_offset_s is applied without estimation (the true ones: the trajectory as good as estimated);
# with estimation the given values are the start, and s2 as the time reference gives offsets against s2.
python3 - "$d" <<'PY'
import json, sys
d = sys.argv[1]
st = json.load(open(d + "/turn/stations.json"))
for s in st["stations"]:
    s["located"] = d + "/turn/" + s["located"]
known = json.loads(json.dumps(st))
known["stations"][1]["time_offset_s"] = 0.0043; known["stations"][2]["time_offset_s"] = -0.0117
json.dump(known, open(d + "/known.json", "w"), indent=2)
ref2 = json.loads(json.dumps(st)); ref2["stations"][1]["time_reference"] = True
ref2["stations"][1]["time_offset_s"] = 0.0043
json.dump(ref2, open(d + "/ref2.json", "w"), indent=2)
bad = json.loads(json.dumps(st)); bad["stations"][2]["time_offset_s"] = "4 ms"
json.dump(bad, open(d + "/bad_offset.json", "w"), indent=2)
two = json.loads(json.dumps(st)); two["stations"][0]["time_reference"] = True; two["stations"][2]["time_reference"] = True
json.dump(two, open(d + "/two_refs.json", "w"), indent=2)
notbool = json.loads(json.dumps(st)); notbool["stations"][0]["time_reference"] = "yes"
json.dump(notbool, open(d + "/ref_not_bool.json", "w"), indent=2)
one = json.loads(json.dumps(st)); one["stations"] = one["stations"][:1]
json.dump(one, open(d + "/one.json", "w"), indent=2)
PY
rk-intersect --stations "$d/known.json" -o "$d/known.csv" --quiet
rk-intersect --stations "$d/ref2.json" -o "$d/ref2.csv" --estimate-time-offsets --report "$d/ref2.json.report" --quiet
python3 - "$d" <<'PY'
import csv, json, sys
d = sys.argv[1]
tr = {row["t_s"]: row for row in csv.DictReader(open(d + "/turn/truth.csv"))}
s2, n = 0.0, 0
for row in csv.DictReader(open(d + "/known.csv")):
    if row["status"] != "ok" or row["t_s"] not in tr: continue
    for c in "enu":
        e = float(row[c + "_m"]) - float(tr[row["t_s"]][c + "_m"]); s2 += e * e; n += 1
assert (s2 / n) ** 0.5 < 0.5, (s2 / n) ** 0.5
t = json.load(open(d + "/ref2.json.report"))["time_offsets"]
assert t["s2"]["reference"] and t["s2"]["offset_s"] == 0.0043 and t["s2"]["sigma_s"] == 0, t["s2"]
# s1 against s2's clock: s1's t_s + offset is s2's t_s + 0.0043, i.e. s1's offset is 0 (the truth's frame).
assert abs(t["s1"]["offset_s"] - 0.0) < 3 * t["s1"]["sigma_s"], t["s1"]
assert abs(t["s3"]["offset_s"] + 0.0117) < 3 * t["s3"]["sigma_s"], t["s3"]
PY
# Bad input: SPEC §4 exit 3, the file's line and column, no output.
o=$d/bad.csv
L 3 "$o" 'bad_offset.json:[0-9]+:[0-9]+: stations\[2\]\.time_offset_s must be a number' -- rk-intersect --stations "$d/bad_offset.json" -o "$o" --estimate-time-offsets
L 3 "$o" 'bad_offset.json:[0-9]+:[0-9]+: stations\[2\]\.time_offset_s must be a number' -- rk-intersect --stations "$d/bad_offset.json" -o "$o"
L 3 "$o" "two_refs.json:[0-9]+:[0-9]+: two stations are the time reference \('s1' and 's3'\)" -- rk-intersect --stations "$d/two_refs.json" -o "$o" --estimate-time-offsets
L 3 "$o" 'ref_not_bool.json:[0-9]+:[0-9]+: stations\[0\]\.time_reference must be true or false' -- rk-intersect --stations "$d/ref_not_bool.json" -o "$o" --estimate-time-offsets
L 3 "$o" 'one.json:[0-9]+:[0-9]+: rk-intersect needs at least two stations' -- rk-intersect --stations "$d/one.json" -o "$o" --estimate-time-offsets
L 2 "$o" 'time-offsets' -- rk-sim multistation --out "$d/x" --time-offsets s9:0.1
L 2 "$o" 'time-offsets' -- rk-sim multistation --out "$d/x" --time-offsets s2:abc
echo ok
