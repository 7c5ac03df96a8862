#!/usr/bin/env bash
# CLI test rk_nightly_interrupted: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/interrupted; rm -rf "$d"; mkdir -p "$d/bin"
standin_rk_run "$d/bin/rk-run"
# Interrupted (SIGTERM) while the first of three trials runs (-j 1): that one failed (stopped), the two that
# never started are "not started", not failed; exit 1.
r=$d/root; mkdir -p "$r/slow" "$r/t2" "$r/t3"
for t in slow t2 t3; do echo '{}' > "$r/$t/trial.json"; done
rk-nightly "$r" -j 1 --rk-run "$d/bin/rk-run" -q > "$d/nightly.out" 2>&1 & pid=$!
for _ in $(seq 200); do [ -e "$r/slow/started" ] && break; sleep 0.05; done
kill -TERM "$pid"; set +e; wait "$pid"; rc=$?; set -e
cat "$d/nightly.out"
test "$rc" = 1
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = \
  "{'done': 0, 'up_to_date': 0, 'skipped_locked': 0, 'failed': 1, 'not_started': 2}"
test "$(json "$r/rk-nightly-summary.json" '[t["result"] for t in d["trials"]]')" = \
  "['failed', 'not-started', 'not-started']"
grep -q ', 2 not started$' "$d/nightly.out"
echo ok
