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
# CI also installs clang and builds the libFuzzer harnesses (build-fuzz/, tests/fuzz) for a smoke run of
# a few seconds each after the suite; RK_FUZZ_TEST=1 does the same here.
# tshark (Wireshark's ASTERIX dissector) is the independent decoder of the radar-feed test: always installed.
# The aravis: capture test runs Aravis' software GigE camera in a private network namespace: always installed.
# The OGC KML 2.2 schema and xmllint validate rk-export's KML: always installed.
SETUP=(--asan-only --tshark --gige --kml-schema)
if [ "${CI:-}" = true ] || [ "${RK_SLURM_TEST:-}" = 1 ]; then SETUP+=(--slurm); fi
FUZZ=0
if [ "${CI:-}" = true ] || [ "${RK_FUZZ_TEST:-}" = 1 ]; then FUZZ=1; SETUP+=(--fuzz); fi
# The report pages are opened in headless Chromium (tests/cli/browser_check.py): CI installs it; elsewhere
# the test is reported skipped when chromium is absent (RK_BROWSER_TEST=1 installs it here too).
if [ "${CI:-}" = true ] || [ "${RK_BROWSER_TEST:-}" = 1 ]; then SETUP+=(--browser); fi
"$ROOT/scripts/setup.sh" "${SETUP[@]}"
JOBS=$(nproc)
# Each phase says when it starts (seconds since the start): the CI budget is watched phase by phase.
echo "== ASan+UBSan build: ctest (set-up and builds took ${SECONDS} s)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$ROOT/build-asan" && ctest --output-on-failure -j"$JOBS")
if [ "$FUZZ" = 1 ]; then
  # Each harness uses one core for RANGEKIT_FUZZ_SMOKE_SECONDS (5) on its committed corpus: one per core
  # (one at a time left a core idle for half of the minute this takes; CI budget, issue 27).
  echo "== libFuzzer harnesses: smoke run (ctest -L fuzz) at ${SECONDS} s"
  (cd "$ROOT/build-fuzz" && ctest --output-on-failure -L fuzz -j"$JOBS")
fi
echo "== test command done in ${SECONDS} s"
