#!/usr/bin/env bash
# Stress version of the kill -9 target (the ctest rk_nightly_kill9 kills twice): N rounds of a forced
# rk-nightly over K trials, each round killed with SIGKILL after a random delay — at even rounds the
# rk-nightly process (its rk-runs and tools die with it), at odd rounds one of its rk-run children
# (rk-nightly goes on and reports that trial failed). After every round every trial's out/ must be
# complete (tests/run/check_out.py re-hashes every product against out/report.json); at the end one
# normal rk-nightly must bring every trial to done/up-to-date with no temporaries left.
#   bench/rk_run_kill_stress.sh [--rounds N] [--trials K] [--max-delay S] [--root DIR]
# Trials are copies of data/sample (6 s, 120 frames). Prints how many kills hit which phase.
set -euo pipefail
SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${RK_BIN:-$SRC/build/apps}
ROUNDS=20; K=4; MAXD=6; ROOT=/tmp/rk-kill-stress
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) ROUNDS=$2; shift 2 ;;
    --trials) K=$2; shift 2 ;;
    --max-delay) MAXD=$2; shift 2 ;;
    --root) ROOT=$2; shift 2 ;;
    *) echo "rk_run_kill_stress.sh: error: unknown option $1" >&2; exit 2 ;;
  esac
done
rm -rf "$ROOT"; mkdir -p "$ROOT"
for k in $(seq 1 "$K"); do cp -r "$SRC/data/sample" "$ROOT/t$k"; done
export PATH=$BIN:$PATH
"$SRC/scripts/rk-nightly" "$ROOT" -q --rk-run "$BIN/rk-run"
bad=0
for round in $(seq 1 "$ROUNDS"); do
  delay=$(awk -v m="$MAXD" -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", rand() * m }')
  "$SRC/scripts/rk-nightly" "$ROOT" --force -q --rk-run "$BIN/rk-run" > /dev/null 2>&1 &
  nightly=$!
  sleep "$delay"
  if [ $((round % 2)) = 0 ]; then
    what="rk-nightly"; kill -9 "$nightly" 2>/dev/null || what="(finished before the kill)"
  else
    child=$(pgrep -P "$nightly" | head -n 1 || true)
    if [ -n "$child" ]; then what="one rk-run (pid $child)"; kill -9 "$child"; else what="(no rk-run running)"; fi
  fi
  wait "$nightly" 2>/dev/null || true
  for k in $(seq 1 "$K"); do flock -w 60 "$ROOT/t$k/.rk-run.lock" true; done
  tmps=$(find "$ROOT" -maxdepth 2 -name 'out.tmp.*' | wc -l)
  if python3 "$SRC/tests/run/check_out.py" "$ROOT"/t* > /tmp/rk-kill-stress.check; then r=ok; else r=FAIL; bad=$((bad + 1)); fi
  echo "round $round: kill -9 $what after $delay s: out/ $r ($tmps stale out.tmp left for the next run)"
  [ "$r" = ok ] || cat /tmp/rk-kill-stress.check
done
"$SRC/scripts/rk-nightly" "$ROOT" -q --rk-run "$BIN/rk-run" || bad=$((bad + 1))
python3 "$SRC/tests/run/check_out.py" --no-temporaries "$ROOT"/t* || bad=$((bad + 1))
echo "rounds: $ROUNDS, failures: $bad"
exit $((bad > 0))
