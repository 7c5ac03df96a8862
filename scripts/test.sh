#!/usr/bin/env bash
# Set-up (scripts/setup.sh --asan), then every test: the Release build and the
# ASan+UBSan build, each through ctest. Exits non-zero if any test fails.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" --asan
JOBS=$(nproc)
echo "== Release build: ctest"
(cd "$ROOT/build" && ctest --output-on-failure -j"$JOBS")
echo "== ASan+UBSan build: ctest"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$ROOT/build-asan" && ctest --output-on-failure -j"$JOBS")
