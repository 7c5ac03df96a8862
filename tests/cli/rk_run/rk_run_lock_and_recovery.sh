#!/usr/bin/env bash
# CLI test rk_run_lock_and_recovery: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
t=$data/run/lock; fresh "$t"
rk-run "$t" --no-plots -q
flock -o "$t/.rk-run.lock" sleep 2 & holder=$!
while flock -n "$t/.rk-run.lock" true; do sleep 0.05; done   # until the holder has it
"$expect" 4 - "locked by another rk-run" -- rk-run "$t" --no-plots
rk-run "$t" --no-plots --wait-lock 60 -q   # waits for the holder, then finds it up to date
wait "$holder"
# Stale temporaries are removed; a swap cut between its two renames is completed from out.old.*.
mkdir -p "$t/out.tmp.AAAAAA/az"; echo partial > "$t/out.tmp.AAAAAA/az/track.csv"
mv "$t/out" "$t/out.old.BBBBBB"
rk-run "$t" --no-plots > "$data/run/lock.out"; cat "$data/run/lock.out"
grep -q 'up-to-date' "$data/run/lock.out"    # the restored out/ is the complete previous one
grep -q 'restored out/ from out.old.BBBBBB' "$t/rk-run.log"
grep -q 'removed stale out.tmp.AAAAAA' "$t/rk-run.log"
check_out --no-temporaries "$t"
echo ok
