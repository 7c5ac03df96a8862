#!/usr/bin/env bash
# golden_outputs_catches_a_change SRC DATA BIN: the golden check (scripts/golden_outputs.py --no-run on the work
# folder that the golden_outputs test left, fixture golden_work) fails when one number of it is changed by 1e-6,
# whether the number is compared byte for byte or with a tolerance, and passes a change within a tolerance.
# Each change is undone before the next (and on exit).
set -eu
src=$1 data=$2 bin=$3
g=$data/golden; digests=$src/tests/golden/outputs.txt; log=$data/golden_change.log
# The files changed below only (the whole folder takes seconds: its videos are decoded).
only='^file (beacon/out/az/located\.csv|kf\.csv|kf\.json|theo/out/theo/axis\.csv)$'
check() {
  python3 "$src/scripts/golden_outputs.py" "$bin" "$g" --check "$digests" --no-run --only "$only" > "$log" 2>&1
}
saved=""
restore() { if [ -n "$saved" ]; then cp -p "$data/golden_change.orig" "$g/$saved"; saved=""; fi; }
trap restore EXIT
# change FILE WHAT DELTA: adds DELTA to one number of WORK/FILE — a CSV's column in the first row, or a JSON member
# (its path, /a/b/0) — written with the digits it had (Decimal arithmetic).
change() {
  restore; saved=$1; cp -p "$g/$1" "$data/golden_change.orig"
  python3 - "$g/$1" "$2" "$3" <<'PY'
import json, re, sys
from decimal import Decimal
path, what, delta = sys.argv[1], sys.argv[2], Decimal(sys.argv[3])
text = open(path).read()
def bump(s):
    d = Decimal(s) + delta
    return format(d, "f") if "e" not in s.lower() else repr(float(d))
if path.endswith(".csv"):
    lines = text.split("\n")
    head = next(i for i, l in enumerate(lines) if l and not l.startswith("#"))
    j = lines[head].split(",").index(what)
    cells = lines[head + 1].split(",")
    cells[j] = bump(cells[j])
    lines[head + 1] = ",".join(cells)
    text = "\n".join(lines)
else:  # the member's number, found by its key path in the file's own text (one replacement)
    doc = json.loads(text)
    v = doc
    for k in what.strip("/").split("/"):
        v = v[int(k)] if isinstance(v, list) else v[k]
    old = repr(v)
    assert text.count(old) >= 1, old
    text = text.replace(old, bump(old), 1)
open(path, "w").write(text)
PY
}
expect_fail() {
  if check; then echo "FAIL: the check passed after: $*"; cat "$log"; exit 1; fi
  grep -q "$1" "$log" || { echo "FAIL: the check did not name $1:"; cat "$log"; exit 1; }
  echo "caught: $*"
}
check || { echo "FAIL: the unchanged work folder does not pass:"; cat "$log"; exit 1; }
change beacon/out/az/located.csv az_deg 1e-6
expect_fail 'file beacon/out/az/located.csv (digest)' "located az + 1e-6 (exact)"
change kf.csv a_range_m 1e-6
expect_fail 'kf.csv  a_range_m' "kf.csv range bias + 1e-6 (tolerance 2e-9)"
change kf.json /estimate/a/az_deg 1e-6
expect_fail 'kf.json  /estimate/a/az_deg' "kf.json az bias + 1e-6 (tolerance 1e-10)"
change theo/out/theo/axis.csv yaw_deg 0.005
expect_fail 'axis.csv  yaw_deg' "image-fit yaw + 0.005 deg = 0.11 sigma (tolerance 0.063 sigma)"
change theo/out/theo/axis.csv yaw_deg 1e-6     # within the fit's tolerance (0.00002 sigma): passes
if ! check; then echo "FAIL: a change of 1e-6 deg in the image fit's yaw failed the check:"; cat "$log"; exit 1; fi
restore
echo ok
