#!/usr/bin/env bash
# CLI test rk_outputs_plot: registered, and described, in tests/cli/rk_outputs.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$data/outputs/plot; rm -rf "$o"; mkdir -p "$o"
p() { python3 "$src/scripts/rk-plot" -i "$d/turret.csv" --columns az_deg "$@"; }
p -o "$o/ref.png"
test "$(head -c 4 "$o/ref.png" | tail -c 3)" = PNG
echo old > "$o/target.png"; ln -s target.png "$o/link.png"
p -o "$o/link.png"; test -L "$o/link.png"; cmp "$o/ref.png" "$o/target.png"
mkfifo "$o/fifo"; cat "$o/fifo" > "$o/from_fifo.png" & reader=$!
p -o "$o/fifo"; wait $reader; cmp "$o/ref.png" "$o/from_fifo.png"; test -p "$o/fifo"
p -o - > "$o/stdout.png"; cmp "$o/ref.png" "$o/stdout.png"
p -o /dev/stdout | cat > "$o/pipe.png"; cmp "$o/ref.png" "$o/pipe.png"
echo ok
