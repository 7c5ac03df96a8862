#!/usr/bin/env bash
# CLI test rk_run_interrupted_page: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/safety/interrupt; rm -rf "$d"; mkdir -p "$d/bin"
t=$d/trial
fresh "$t"
# The real tools, but an rk-report that says it started and then takes its time.
real=$(dirname "$(command -v rk-run)")
for f in "$real"/rk-*; do ln -s "$f" "$d/bin/$(basename "$f")"; done
rm -f "$d/bin/rk-report"
printf '#!/bin/sh\ntouch "%s/page-started"\nexec sleep 30\n' "$d" > "$d/bin/rk-report"
chmod +x "$d/bin/rk-report"
"$d/bin/rk-run" "$t" --bin "$d/bin" -q > /dev/null 2> "$d/err" &
pid=$!
for _ in $(seq 1 600); do [ -e "$d/page-started" ] && break; sleep 0.1; done
[ -e "$d/page-started" ] || { echo "FAIL: the report page never started"; kill $pid; exit 1; }
kill -TERM $pid
set +e; wait $pid; rc=$?; set -e
cat "$d/err"
[ $rc = 1 ] || { echo "FAIL: SIGTERM during the report page: exit $rc, expected 1"; exit 1; }
test "$(json "$t/last-run.json" 'd["result"]')" = failed
json "$t/last-run.json" 'd["error"]' | grep -q 'interrupted by signal 15'
check_out --no-temporaries "$t"
echo ok
