#!/usr/bin/env bash
# CLI test rk_intersect_duplicates: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/intersect; o=$d/dup; rm -rf "$o"; mkdir -p "$o"
# A duplicated record (a logger that wrote a row twice): station s2's located file with its 5th data row twice
# (no ids), and the ids file of rk_intersect_ids' kind with one (id, time) row twice.
python3 - "$d/trial/stations.json" "$o" <<'PY'
import csv, json, os, sys
st = json.load(open(sys.argv[1])); o = sys.argv[2]; base = os.path.dirname(sys.argv[1])
plain, dup, ids, ids_dup = (json.loads(json.dumps(st)) for _ in range(4))
for k, s in enumerate(st["stations"]):
    src = os.path.join(base, s["located"])
    lines = open(src).read().splitlines(True)
    head = next(i for i, l in enumerate(lines) if not l.startswith("#"))
    plain["stations"][k]["located"] = src
    dup["stations"][k]["located"] = src
    if s["name"] == "s2":
        with open(os.path.join(o, "s2_dup.csv"), "w") as f:
            f.writelines(lines[:head + 6] + [lines[head + 5]] + lines[head + 6:])
        dup["stations"][k]["located"] = os.path.join(o, "s2_dup.csv")
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    cols = list(rows[0].keys())
    i = cols.index("t_s") + 1
    for name, twice in (("ids", False), ("ids_dup", True)):
        out = os.path.join(o, "%s_%s.csv" % (s["name"], name))
        with open(out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(cols[:i] + ["id"] + cols[i:])
            for n, r in enumerate(rows):
                for pid in ("a", "b"):
                    v = [r[c] for c in cols]
                    w.writerow(v[:i] + [pid] + v[i:])
                    if twice and s["name"] == "s2" and n == 7 and pid == "b":
                        w.writerow(v[:i] + [pid] + v[i:])
        (ids if name == "ids" else ids_dup)["stations"][k]["located"] = out
for name, j in (("plain", plain), ("dup", dup), ("ids", ids), ("ids_dup", ids_dup)):
    json.dump(j, open(os.path.join(o, name + ".json"), "w"))
PY
line=$(( $(grep -c '^#' "$o/s2_dup.csv" || true) + 7 ))   # the second copy: header, five rows, the copy
# Without --bad-rows skip: exit 3 at the repeated time, no output, the report written.
"$expect" 3 "$o/out.csv" "s2_dup.csv:$line:1:" -- rk-intersect --stations "$o/dup.json" -o "$o/out.csv"
"$expect" 3 "$o/out.csv" "s2_ids_dup.csv:18:1: .*'b'" -- rk-intersect --stations "$o/ids_dup.json" -o "$o/out.csv"
fails 3 "$o/fail.json" "$o/out.csv" -- rk-intersect --stations "$o/dup.json" -o "$o/out.csv" --report "$o/fail.json"
# With it: the copy is dropped with a warning naming it, and the trajectory is the one without the copy.
rk-intersect --stations "$o/plain.json" -o "$o/plain.csv" -q
rk-intersect --stations "$o/dup.json" -o "$o/skip.csv" --bad-rows skip --report "$o/skip.json" 2> "$o/skip.err"
cmp "$o/plain.csv" "$o/skip.csv"
grep -q "s2_dup.csv:$line:1: .*repeats" "$o/skip.err"
rk-intersect --stations "$o/ids.json" -o "$o/ids.csv" -q
rk-intersect --stations "$o/ids_dup.json" -o "$o/ids_skip.csv" --bad-rows skip 2> "$o/ids_skip.err"
cmp "$o/ids.csv" "$o/ids_skip.csv"
grep -q "s2_ids_dup.csv:18:1: .*repeats for id 'b'" "$o/ids_skip.err"
python3 - "$o/skip.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
skipped = {k: v.get("rows_skipped") for k, v in r["inputs"].items() if isinstance(v, dict) and v.get("rows_skipped")}
assert list(skipped.values()) == [1], skipped
PY
echo ok
