#!/usr/bin/env bash
# CLI test extract_cli_beacon_streams: registered, and described, in tests/cli/rk_extract.cmake.
# Proof by ordering, not by time: the sixth image of the sequence (frame 5) is a FIFO that nobody writes while
# the test reads, so rk-extract is blocked opening it; the header and the rows of frames 0-4 must already have
# come through the pipe (a tool that wrote at the end would never send them, and the read would wait for the
# watchdog). Then the FIFO is opened and closed empty: frame 5 is not an image, so the run fails with its
# one-line error and exit 3 after the rows it streamed (stdout cannot take them back). The same input with
# -o FILE leaves no file (files stay atomic), and -o - of a good sequence equals -o FILE byte for byte.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract
d=$x/stream
rm -rf "$d"; mkdir -p "$d/seq"
for k in 1 2 3 4 5; do cp "$x/seq/00000$k.png" "$d/seq/"; done   # the sequence counts from 1 (make_inputs.sh)
mkfifo "$d/seq/000006.png" "$d/out.fifo"
rk-extract beacon --video "$d/seq/%06d.png" --fps 20 --t0 0 -o - --report "$d/report.json" >"$d/out.fifo" 2>"$d/err" &
pid=$!
exec 3<"$d/out.fifo"
got=0
: >"$d/rows.csv"
# read -t is a watchdog, not a timing assertion: if the rows never come, fail instead of hanging.
while [ "$got" -lt 6 ] && IFS= read -r -t 120 line <&3; do
  printf '%s\n' "$line" >>"$d/rows.csv"
  got=$((got + 1))
done
[ "$got" = 6 ] || { echo "only $got lines arrived before frame 5" >&2; kill "$pid"; exit 1; }
head -n 1 "$d/rows.csv" | grep -qx 'frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px'
[ "$(cut -d, -f1 "$d/rows.csv" | tail -n 5 | tr '\n' ' ')" = "0 1 2 3 4 " ]
: >"$d/seq/000006.png"   # frame 5: opened and closed empty
cat <&3 >>"$d/rows.csv"
exec 3<&-
rc=0; wait "$pid" || rc=$?
[ "$rc" = 3 ] || { echo "exit $rc, expected 3"; cat "$d/err"; exit 1; }
[ "$(wc -l <"$d/err")" = 1 ] && grep -q '000006.png' "$d/err" || { cat "$d/err"; exit 1; }
[ "$(wc -l <"$d/rows.csv")" = 6 ]   # nothing after the error
grep -q '"status": *"failed"' "$d/report.json"
# Files stay atomic: the same failure with -o FILE writes no file.
rm -f "$d/seq/000006.png"; printf 'not a png' >"$d/seq/000006.png"
rc=0; rk-extract beacon --video "$d/seq/%06d.png" --fps 20 --t0 0 -o "$d/track.csv" 2>"$d/err2" || rc=$?
[ "$rc" = 3 ] && [ ! -e "$d/track.csv" ]
# A good run: what streamed equals the file.
rm "$d/seq/000006.png"
rk-extract beacon --video "$d/seq/%06d.png" --fps 20 --t0 0 -o "$d/track.csv"
rk-extract beacon --video "$d/seq/%06d.png" --fps 20 --t0 0 -o - | cat >"$d/piped.csv"
cmp "$d/track.csv" "$d/piped.csv"
