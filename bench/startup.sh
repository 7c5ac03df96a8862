#!/usr/bin/env bash
# Start-up cost of the tools: CPU seconds of `TOOL --help` (nothing read, nothing computed), the floor of
# every tool invocation — rk-run starts one per step and the test suite thousands — and the number of
# shared libraries each tool loads (docs/benchmarks.md "Issue 27 — start-up"). Median of REPEATS runs, user +
# system CPU from /usr/bin/time; under ASan set ASAN_OPTIONS as the test command does.
#   bench/startup.sh [BINDIR] [REPEATS]      defaults: build/apps of this checkout, 15
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${1:-$ROOT/build/apps}
N=${2:-15}
echo "# $BIN; nproc $(nproc); load $(cut -d' ' -f1-3 /proc/loadavg); ASAN_OPTIONS=${ASAN_OPTIONS:-}"
printf '%-14s %6s %12s\n' tool libs "cpu_s(median)"
for tool in rk-locate rk-smooth rk-extract rk-intersect rk-run rk-sim rk-calibrate rk-attitude; do
  [ -x "$BIN/$tool" ] || continue
  libs=$(ldd "$BIN/$tool" | wc -l)
  cpu=$(for _ in $(seq "$N"); do
          /usr/bin/time -f '%U %S' "$BIN/$tool" --help 2>&1 >/dev/null | tail -n 1
        done | awk '{ print $1 + $2 }' | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
  printf '%-14s %6d %12.3f\n' "$tool" "$libs" "$cpu"
done
