#!/usr/bin/env bash
# CLI test rk_run_deep_manifest: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/safety/deep; rm -rf "$d"; mkdir -p "$d"
t=$d/trial
nest() {  # nest FILE N: an extra key nested N levels deep
  python3 - "$1" "$2" <<'PY'
import json, sys
path, n = sys.argv[1], int(sys.argv[2])
text = open(path).read().rstrip()
assert text.endswith("}")
open(path, "w").write(text[:-1] + ', "extra": ' + "[" * n + "]" * n + "}\n")
PY
}
# Deeper than any real file (5000 levels): refused at its place (exit 3), not a crash.
fresh "$t"; nest "$t/trial.json" 5000
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: nested deeper than 512 levels" -- rk-run "$t" --no-plots
# Deep but within the limit (300 levels): an extra key is kept, the run and its page are made.
fresh "$t"; nest "$t/trial.json" 300
rk-run "$t" -q
test -s "$t/out/report.html" || { echo "FAIL: no page for a trial with a deep extra key"; exit 1; }
echo ok
