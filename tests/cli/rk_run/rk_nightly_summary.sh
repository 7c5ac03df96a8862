#!/usr/bin/env bash
# CLI test rk_nightly_summary: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
r=$data/run/nightly; rm -rf "$r"; mkdir -p "$r/site"
fresh "$r/t1"; fresh "$r/site/t2"; fresh "$r/site/t3"
awk -F, 'NR == 4 { $2 = "x" } { print }' OFS=, "$r/site/t3/range.csv" > "$r/tmp" && mv "$r/tmp" "$r/site/t3/range.csv"
set +e; rk-nightly "$r" -j 2 --no-plots > "$data/run/nightly1.out" 2>&1; rc=$?; set -e
cat "$data/run/nightly1.out"
test "$rc" = 1
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 2, 'up_to_date': 0, 'skipped_locked': 0, 'failed': 1}"
json "$r/rk-nightly-summary.json" '[t for t in d["trials"] if t["trial"]=="site/t3"][0]["reason"]' | grep -q 'range.csv:4:'
grep -Eq '^site/t3 +failed' "$r/rk-nightly-summary.txt"
grep -q 'summary:' "$r/rk-nightly.log"
check_out --no-temporaries "$r/t1" "$r/site/t2"
check_out --allow-missing --no-temporaries "$r/site/t3"
cp "$data/small/range.csv" "$r/site/t3/range.csv"
rk-nightly "$r" --no-plots -q     # quiet and successful: prints nothing
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 1, 'up_to_date': 2, 'skipped_locked': 0, 'failed': 0}"
# The holder's output goes to a file: a sleep left on the test's stdout kept ctest waiting for its 60 s.
flock -o "$r/.rk-nightly/lock" sleep 60 > "$data/run/nightly_holder.out" 2>&1 & holder=$!
while flock -n "$r/.rk-nightly/lock" true; do sleep 0.05; done
set +e; timeout 30 rk-nightly "$r" --no-plots 2> "$data/run/nightly2.err"; rc=$?; set -e
kill $(pgrep -P "$holder") "$holder"; wait "$holder" 2>/dev/null || true
test "$rc" = 75; grep -q 'another rk-nightly' "$data/run/nightly2.err"   # at once, not after the holder
echo ok
