#!/usr/bin/env bash
# Set-up (scripts/setup.sh --asan), then every test: the Release build and the
# ASan+UBSan build, each through ctest. Exits non-zero if any test fails.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# CI (CI=true, root) also installs Slurm so that the one-node Slurm test runs; elsewhere it is skipped
# unless Slurm is installed (RK_SLURM_TEST=1 installs it here too).
if [ "${CI:-}" = true ] || [ "${RK_SLURM_TEST:-}" = 1 ]; then
  "$ROOT/scripts/setup.sh" --asan --slurm
else
  "$ROOT/scripts/setup.sh" --asan
fi
JOBS=$(nproc)
echo "== Release build: ctest"
(cd "$ROOT/build" && ctest --output-on-failure -j"$JOBS")
echo "== ASan+UBSan build: ctest"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$ROOT/build-asan" && ctest --output-on-failure -j"$JOBS")
