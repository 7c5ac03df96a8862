#!/usr/bin/env bash
# CLI test rk_run_own_files_no_links: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/safety/ownfiles; rm -rf "$d"; mkdir -p "$d"
t=$d/trial
printf 'precious\n' > "$d/victim"
# Each file rk-run makes for itself in the trial folder, made a link to a file outside by whoever can
# write the folder: rk-run refuses (exit 4, one line naming it) and the file outside is untouched.
for f in .rk-run.lock last-run.json rk-run.log; do
  fresh "$t"
  ln -s "$d/victim" "$t/$f"
  "$expect" 4 "$t/out" "$f: is a symbolic link" -- rk-run "$t" --no-plots
  [ "$(cat "$d/victim")" = precious ] || { echo "FAIL: $f: the link's target was written"; exit 1; }
  # The link itself may be removed (last-run.json must not keep saying anything), never replaced by a file
  # written through it.
  [ -L "$t/$f" ] || [ ! -e "$t/$f" ] || { echo "FAIL: $f: the link was replaced by a file"; exit 1; }
done
# Stale working folders that are links to folders outside: never followed, never removed.
fresh "$t"
mkdir -p "$d/elsewhere"; printf '{}\n' > "$d/elsewhere/report.json"; printf 'x\n' > "$d/elsewhere/keep"
ln -s "$d/elsewhere" "$t/out.tmp.AAAAAA"
ln -s "$d/elsewhere" "$t/out.old.BBBBBB"
rk-run "$t" --no-plots -q
test -f "$d/elsewhere/report.json" && test -f "$d/elsewhere/keep" || { echo "FAIL: a linked out.tmp was emptied"; exit 1; }
# A step option that abbreviates a real option (argparse would expand --out to --output): refused at its
# place in trial.json before any step runs; nothing outside is written.
fresh "$t"
python3 - "$t/trial.json" "$d/victim" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"az/plot": {"out": sys.argv[2]}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: steps.az/plot.out: 'out' is not an option of rk-plot" -- rk-run "$t"
[ "$(cat "$d/victim")" = precious ] || { echo "FAIL: the step option overwrote a file outside"; exit 1; }
# rk-run's output options come after the user's (a tool whose parser lets the last one win still writes
# where rk-run says).
fresh "$t"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"az/plot": {"title": "mine"}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" -q
python3 - "$t/out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
s = [s for s in r["steps"] if s["id"] == "az/plot-located"][0]
cl = s["command_line"]
assert cl.index("--title") < cl.index("-o"), cl
PY
echo ok
