#!/usr/bin/env bash
# CLI test import_cli_asterix: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/import/asterix
/usr/bin/python3 "$src/tests/cli/rk_import/make_asterix.py" "$d"
epoch=2016-05-05T23:59:50Z
# The redundant feed over midnight: 24 plots (each once), in time order, the 3-D radar's el from its height.
rk-import asterix --input "$d/feed.pcap" --radars "$d/radars.json" --epoch-utc $epoch -o "$d/plots.csv" \
  --report "$d/plots.json" 2> "$d/plots.err"
cat "$d/plots.err"
grep -q "SAC 25 SIC 11 is not in --radars: named 25-11" "$d/plots.err"
/usr/bin/python3 - "$d/plots.csv" "$d/truth.csv" "$d/plots.json" <<'PY'
import csv, json, math, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
truth = list(csv.DictReader(open(sys.argv[2])))
assert list(rows[0].keys()) == "t_s,radar,range_m,az_deg,el_deg,track_id,sac,sic,flight_level,height_m,mode3a,address,el_source".split(","), rows[0].keys()
assert len(rows) == len(truth) == 24, (len(rows), len(truth))
for r, t in zip(rows, truth):
    assert abs(float(r["t_s"]) - float(t["t_s"])) < 1e-6 and r["radar"] == t["radar"], (r, t)
    assert r["mode3a"] == "4321" and r["address"] == "123456" and r["track_id"] == "42", r
    if r["radar"] == "north":
        # 25 000 ft at 60 NM from 150 m: about 3.35 deg up (a flat earth would say 3.80 deg). Independently: the
        # sphere of the meridian's radius of curvature at 45.5 deg (the azimuths are within 2 deg of north).
        s = math.sin(math.radians(45.5)); e2 = 0.0066943799901
        R = 6378137 * (1 - e2) / (1 - e2 * s * s) ** 1.5
        rng, ra, rt = float(r["range_m"]), R + 150, R + 25000 * 0.3048
        el = math.degrees(math.asin((rt * rt - ra * ra - rng * rng) / (2 * ra * rng)))
        assert r["el_source"] == "3d" and abs(float(r["el_deg"]) - el) < 0.002, (r, el)
    else:
        assert r["el_source"] == "" and r["el_deg"] == "", r
az = [float(r["az_deg"]) for r in rows if r["radar"] == "north"]
assert az[0] > 359 and az[-1] < 2, az  # across 0/360, never folded
rep = json.load(open(sys.argv[3]))
a = rep["asterix"]
assert a["duplicates"] == 24 and a["bad_records"] == 0, a
north = [r for r in a["radars"] if r["name"] == "north"][0]
assert north["north_markers"] == 3 and north["scan_period_s"] == 4.0 and north["antenna_rotation_period_s"] == 4.0, north
assert sorted(s["duplicates"] for s in a["sources"]) == [0, 0, 24], a["sources"]
PY
# The raw stream of the same reports: its date from --epoch-utc, the same plots.
rk-import asterix --input "$d/feed.ast" --radars "$d/radars.json" --epoch-utc $epoch -o "$d/raw.csv" 2> /dev/null
diff <(grep -v '^#' "$d/plots.csv") <(grep -v '^#' "$d/raw.csv")
# Two inputs, one after the other (bad.pcap holds feed.pcap's first report again: written once), and stdout.
rk-import asterix --input "$d/bad.pcap" --input "$d/feed.pcap" --epoch-utc $epoch -o - 2> /dev/null | grep -vc '^#' | grep -qx 25
# Bad records: skipped with file, byte offset and packet; counted; exit 0.
rk-import asterix --input "$d/bad.pcap" --epoch-utc $epoch -o "$d/bad.csv" --report "$d/bad.json" 2> "$d/bad.err"
cat "$d/bad.err"
grep -q "warning: .*bad.pcap: byte [0-9]*: data block length runs past the end of the datagram (CAT048) (packet 3): skipped" "$d/bad.err"
grep -q "warning: .*bad.pcap: byte [0-9]*: FSPEC sets a field reference number its UAP does not use (CAT001) (packet 4)" "$d/bad.err"
grep -q '"bad_records": 2' "$d/bad.json"
# --bad-records error: exit 3 naming the byte, no output, the report still written (failed).
"$expect" 3 "$d/bad2.csv" "bad.pcap: byte [0-9]+: data block length runs past the end of the datagram" -- \
  rk-import asterix --input "$d/bad.pcap" --epoch-utc $epoch -o "$d/bad2.csv" --bad-records error --report "$d/bad2.json"
grep -q '"status": "failed"' "$d/bad2.json"
# radars.json errors name line and column; a file named .pcap that is not one; a missing input; a bad epoch.
printf '{"radars": [\n  {"name": "r1", "sac": 25, "sic": 999}\n]}\n' > "$d/badradars.json"
"$expect" 3 "$d/x.csv" "badradars.json:2:[0-9]+: radars\[0\].sic must be in \[0, 255\]" -- \
  rk-import asterix --input "$d/feed.pcap" --radars "$d/badradars.json" --epoch-utc $epoch -o "$d/x.csv"
printf 'not a capture' > "$d/fake.pcap"
"$expect" 3 "$d/x.csv" "fake.pcap: byte 0: named as a packet capture but is not pcap or pcapng" -- \
  rk-import asterix --input "$d/fake.pcap" --epoch-utc $epoch -o "$d/x.csv"
"$expect" 4 "$d/x.csv" "missing.pcap" -- rk-import asterix --input "$d/missing.pcap" --epoch-utc $epoch -o "$d/x.csv"
"$expect" 2 "$d/x.csv" "--epoch-utc" -- rk-import asterix --input "$d/feed.pcap" --epoch-utc 2016-13-01T00:00:00Z -o "$d/x.csv"
"$expect" 2 "$d/x.csv" "--bad-records" -- rk-import asterix --input "$d/feed.pcap" --epoch-utc $epoch --bad-records maybe -o "$d/x.csv"
# The input is never the output.
before=$(sha256sum < "$d/feed.pcap")
"$expect" 2 - -- rk-import asterix --input "$d/feed.pcap" --epoch-utc $epoch -o "$d/feed.pcap"
[ "$(sha256sum < "$d/feed.pcap")" = "$before" ]
echo PASS
