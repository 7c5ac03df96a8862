#!/usr/bin/env bash
# Set-up (scripts/setup.sh --asan-only), then every test (unit and CLI, through ctest) on the ASan+UBSan
# build in build-asan/: every binary the CLI tests run is the sanitized one. Exits non-zero if any test
# fails. The Release build (scripts/setup.sh) is the one for the demo and the benchmarks; building it
# here as well would double the build time for no test the sanitized build does not already run
# (ctest in build/ runs the same suite on it).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# CI (CI=true, root) also installs Slurm so that the one-node Slurm test runs; elsewhere it is skipped
# unless Slurm is installed (RK_SLURM_TEST=1 installs it here too).
if [ "${CI:-}" = true ] || [ "${RK_SLURM_TEST:-}" = 1 ]; then
  "$ROOT/scripts/setup.sh" --asan-only --slurm
else
  "$ROOT/scripts/setup.sh" --asan-only
fi
JOBS=$(nproc)
echo "== ASan+UBSan build: ctest"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$ROOT/build-asan" && ctest --output-on-failure -j"$JOBS")
