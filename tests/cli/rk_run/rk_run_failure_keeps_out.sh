#!/usr/bin/env bash
# CLI test rk_run_failure_keeps_out: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
t=$data/run/fail; fresh "$t"
rk-run "$t" --no-plots -q
before=$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)
awk -F, 'NR == 6 { $3 = "abc" } { print }' OFS=, "$t/turret.csv" > "$t/turret.tmp" && mv "$t/turret.tmp" "$t/turret.csv"
"$expect" 3 - "turret.csv:6:[0-9]+: .*step az/locate" -- rk-run "$t" --no-plots
after=$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)
test "$before" = "$after" || { echo "out/ changed"; exit 1; }
check_out --no-temporaries "$t"
test "$(json "$t/last-run.json" 'd["result"]')" = failed
test "$(json "$t/last-run.json" 'd["exit_code"]')" = 3
json "$t/last-run.json" '[s for s in d["steps"] if s["id"]=="az/locate"][0]["log_tail"][-1]' | grep -q "rk-locate: error: turret.csv:6:"
grep -q 'FAILED' "$t/rk-run.log"; grep -q '  | rk-locate: error: turret.csv:6:' "$t/rk-run.log"
# --report gets the same summary, also on failure.
"$expect" 3 - -- rk-run "$t" --no-plots --report "$data/run/fail_report.json"
test "$(json "$data/run/fail_report.json" 'd["result"]')" = failed
# An option the tool does not have: exit 3 at its place in trial.json, before any step runs (checked against
# the tool's --help).
fresh "$t"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"az/locate": {"no-such-option": 1}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: steps.az/locate.no-such-option: 'no-such-option' is not an option of rk-locate" \
  -- rk-run "$t" --no-plots
check_out --allow-missing --no-temporaries "$t"
# A value the tool rejects: exit 3 (the manifest's "steps" are the bad input).
fresh "$t"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"az/locate": {"sigma-px": "abc"}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
"$expect" 3 "$t/out" "rejected the options of step az/locate" -- rk-run "$t" --no-plots
check_out --allow-missing --no-temporaries "$t"
echo ok
