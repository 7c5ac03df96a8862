#!/usr/bin/env bash
# ctest's fuzz smoke run of one harness: HARNESS CORPUS SCRATCH SECONDS. Runs the committed corpus and
# then fuzzes for SECONDS; new inputs are written to SCRATCH (emptied first), never to CORPUS. Any
# crash, sanitizer report, leak or timeout makes libFuzzer exit non-zero and leaves the input in SCRATCH.
set -euo pipefail
harness=$1 corpus=$2 scratch=$3 seconds=${4:-5}
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
exec "$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$scratch/" "$scratch" "$corpus"
