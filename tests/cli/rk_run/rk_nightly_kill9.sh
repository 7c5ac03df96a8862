#!/usr/bin/env bash
# CLI test rk_nightly_kill9: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
r=$data/run/kill; rm -rf "$r"; mkdir -p "$r"
for k in 1 2 3; do fresh "$r/t$k"; done
rk-nightly "$r" --no-plots -q
for delay in 0.5 1.5; do
  rk-nightly "$r" --no-plots --force -q > /dev/null 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid"; wait "$pid" 2>/dev/null || true
  for k in 1 2 3; do flock -w 20 "$r/t$k/.rk-run.lock" true; done   # the killed tree is gone
  check_out "$r"/t*          # complete out/ everywhere (temporaries may remain until the next run)
done
set +e; rk-nightly "$r" --no-plots > "$data/run/kill.out" 2>&1; rc=$?; set -e
cat "$data/run/kill.out"
test "$rc" = 0
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]["failed"]')" = 0
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]["done"] + d["counts"]["up_to_date"]')" = 3
check_out --no-temporaries "$r"/t*
echo ok
