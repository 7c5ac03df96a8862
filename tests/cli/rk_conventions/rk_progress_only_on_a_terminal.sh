#!/usr/bin/env bash
# CLI test rk_progress_only_on_a_terminal: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/small
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
args=(beacon --video "$T/az/video.mkv" --frames "$T/az/frames.csv")
# stderr not a terminal: nothing on it.
rk-extract "${args[@]}" -o "$out/a.csv" 2> "$out/err.txt"
[ ! -s "$out/err.txt" ] || { echo "FAIL: stderr not a terminal but got:"; cat "$out/err.txt"; exit 1; }
# On a pseudo-terminal (script(1) gives the command one): the progress line and the summary.
frames=$(($(grep -vc '^#' "$T/az/frames.csv") - 1))
script -qec "rk-extract ${args[*]} -o $out/b.csv" /dev/null > "$out/tty.txt" < /dev/null
tr '\r' '\n' < "$out/tty.txt" | sed 's/\x1b\[K//g' > "$out/tty_lines.txt"
grep -Eq "^rk-extract: [0-9]+/$frames frames \([0-9]+%\)" "$out/tty_lines.txt" \
  || { echo "FAIL: no progress line with done/total"; cat -v "$out/tty.txt"; exit 1; }
grep -Eq "^rk-extract: $frames frames: [0-9]+ ok" "$out/tty_lines.txt" \
  || { echo "FAIL: no closing summary line"; cat -v "$out/tty.txt"; exit 1; }
cmp "$out/a.csv" "$out/b.csv"
# --quiet: nothing even on a terminal.
script -qec "rk-extract ${args[*]} -o $out/c.csv --quiet" /dev/null > "$out/quiet.txt" < /dev/null
[ ! -s "$out/quiet.txt" ] || { echo "FAIL: --quiet printed:"; cat -v "$out/quiet.txt"; exit 1; }
echo ok
