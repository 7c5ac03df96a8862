#!/usr/bin/env bash
# CLI test rk_intersect_ids: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/intersect; o=$d/ids; rm -rf "$o"; mkdir -p "$o"
# Each station's located file as rk-locate writes it from a points track: ids a and b with the same rows, and c
# at the first station only.
python3 - "$d/trial/stations.json" "$o" <<'PY'
import csv, json, os, sys
st = json.load(open(sys.argv[1])); o = sys.argv[2]; base = os.path.dirname(sys.argv[1])
for k, s in enumerate(st["stations"]):
    rows = list(csv.DictReader(open(os.path.join(base, s["located"]))))
    cols = list(rows[0].keys())
    out = os.path.join(o, s["name"] + ".csv")
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols[:cols.index("t_s") + 1] + ["id"] + cols[cols.index("t_s") + 1:])
        for r in rows:
            for pid in (["a", "b", "c"] if k == 0 else ["a", "b"]):
                v = [r[c] for c in cols]
                i = cols.index("t_s") + 1
                w.writerow(v[:i] + [pid] + v[i:])
    s["located"] = out
json.dump(st, open(os.path.join(o, "stations.json"), "w"))
PY
rk-intersect --stations "$d/trial/stations.json" -o "$o/plain.csv" --quiet
rk-intersect --stations "$o/stations.json" -o "$o/ids.csv" --report "$o/ids.json" 2> "$o/stderr.txt"
grep -q "point 'c' is seen by 1 station" "$o/stderr.txt"
head -1 "$o/ids.csv" | grep -q '^t_s,id,e_m,n_m,u_m,'
# a's and b's trajectories are the plain one, row for row; no row of c.
for p in a b; do
  grep ",$p," "$o/ids.csv" | sed "s/,$p,/,/" > "$o/$p.csv"
  tail -n +2 "$o/plain.csv" | cmp - "$o/$p.csv"
done
! grep -q ',c,' "$o/ids.csv"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); sys.exit(sorted(r['by_id']) != ['a','b'])" "$o/ids.json"
echo ok
