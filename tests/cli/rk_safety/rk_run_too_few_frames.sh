#!/usr/bin/env bash
# CLI test rk_run_too_few_frames: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/safety/toofew; rm -rf "$d"; mkdir -p "$d"
t=$d/trial
# A trial whose beacon is seen in two frames only: smoothing needs three.
rk-sim beacon --out "$t" --preset small --duration 0.1 --seed 5 --quiet
rk-run "$t" > "$d/run.out" 2> "$d/run.err" || { cat "$d/run.out" "$d/run.err"; echo "FAIL: the run failed"; exit 1; }
cat "$d/run.out"
# What could be made is delivered: extract and locate products, a page that says why smoothing did not run.
test -s "$t/out/az/track.csv" && test -s "$t/out/az/located.csv" || { echo "FAIL: extract/locate products missing"; exit 1; }
grep -Eq '^az/smooth +warning' "$d/run.out" || { echo "FAIL: smooth is not a warning"; exit 1; }
python3 - "$t/out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
s = {x["id"]: x for x in r["steps"]}
assert s["az/smooth"]["status"] == "warning", s["az/smooth"]
why = s["az/smooth"]["reason"]
assert "needs at least 3 samples" in why, why
msgs = json.dumps([{k: x.get(k) for k in ("reason", "error", "log_tail")} for x in r["steps"]])
assert "out.tmp." not in msgs, "a message names a temporary path: " + msgs
PY
grep -q 'needs at least 3 samples' "$t/out/report.html" || { echo "FAIL: the page does not say why"; exit 1; }
if grep -rq 'out\.tmp\.' "$d/run.out" "$d/run.err" "$t/last-run.json"; then echo "FAIL: a temporary path is named"; exit 1; fi
# The second run is up to date (the warning is remembered, nothing downstream is retried).
rk-run "$t" | grep -q up-to-date || { echo "FAIL: second run not up to date"; exit 1; }
echo ok
