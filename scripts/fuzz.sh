#!/usr/bin/env bash
# Long fuzzing runs of the libFuzzer harnesses (tests/fuzz/README.md).
#   scripts/fuzz.sh [HARNESS|all] [SECONDS]     default: all harnesses, 300 s each, one after the other
# Builds the harnesses with clang++ in build-fuzz/ (scripts/setup.sh --fuzz installs clang), runs each
# as ONE fuzzing process starting from the committed corpus tests/fuzz/corpus/HARNESS (never written
# to), keeps what it finds in a scratch folder (RK_FUZZ_WORK, default build-fuzz/fuzz-work/HARNESS/:
# corpus/ new inputs, artifacts/ crashing inputs, log) and prints executions, exec/s, coverage (cov =
# edges, ft = features) and findings per harness. Exit status 1 if any harness found a crash.
# Extra libFuzzer flags: RK_FUZZ_FLAGS="-max_len=4096 ...". Builds under flock RK_BUILD_LOCK if set.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WHICH=${1:-all}
SECONDS_EACH=${2:-300}
BUILD="$ROOT/build-fuzz"
WORK=${RK_FUZZ_WORK:-$BUILD/fuzz-work}
HARNESSES=$(cd "$ROOT/tests/fuzz" && ls fuzz_*.cc | sed 's/\.cc$//')
if [ "$WHICH" != all ]; then
  if ! grep -qx "$WHICH" <<<"$HARNESSES"; then
    echo "fuzz.sh: error: unknown harness '$WHICH' (one of: $(echo $HARNESSES))" >&2
    exit 2
  fi
  HARNESSES=$WHICH
fi
command -v clang++ >/dev/null || { echo "fuzz.sh: error: clang++ not found (scripts/setup.sh --fuzz)" >&2; exit 2; }
LOCK=()
if [ -n "${RK_BUILD_LOCK:-}" ]; then LOCK=(flock "$RK_BUILD_LOCK"); fi
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ -DRANGEKIT_BUILD_FUZZ=ON -DRANGEKIT_BUILD_TESTS=OFF \
    -DRANGEKIT_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" >&2
fi
targets=()
for h in $HARNESSES; do targets+=(--target "$h"); done
"${LOCK[@]}" cmake --build "$BUILD" -j"$(nproc)" "${targets[@]}" >&2

found=0
printf '%-20s %8s %12s %9s %7s %7s %6s %s\n' harness seconds executions exec/s cov ft corpus findings
for h in $HARNESSES; do
  dir="$WORK/$h"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  log="$dir/log"
  set +e
  (cd "$dir" && "$BUILD/tests/fuzz/$h" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 \
     -print_final_stats=1 -artifact_prefix="$dir/artifacts/" ${RK_FUZZ_FLAGS:-} \
     "$dir/corpus" "$ROOT/tests/fuzz/corpus/$h") >"$log" 2>&1
  rc=$?
  set -e
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | grep -o 'cov: [0-9]* ft: [0-9]* corp: [0-9]*' | tail -1)
  cov=$(awk '{print $2}' <<<"$last") ft=$(awk '{print $4}' <<<"$last") corp=$(awk '{print $6}' <<<"$last")
  crashes=$(find "$dir/artifacts" -type f | wc -l)
  what=none
  if [ "$rc" -ne 0 ] || [ "$crashes" -gt 0 ]; then
    found=1
    what="$crashes input(s) in $dir/artifacts (exit $rc; see $log)"
  fi
  printf '%-20s %8s %12s %9s %7s %7s %6s %s\n' "$h" "$SECONDS_EACH" "${execs:-?}" "${rate:-?}" "${cov:-?}" \
    "${ft:-?}" "${corp:-?}" "$what"
done
exit $found
