#!/usr/bin/env bash
# CLI test rk_outputs_locate: registered, and described, in tests/cli/rk_outputs.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/locate; o=$data/outputs/locate; rm -rf "$o"; mkdir -p "$o"
loc() { rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" --quiet "$@"; }
loc -o "$o/ref.csv"
test -s "$o/ref.csv"
# -o -: the data on stdout, nothing else.
loc -o - > "$o/stdout.csv"; cmp "$o/ref.csv" "$o/stdout.csv"
# /dev/stdout into a pipe and into a file: written to the descriptor, /dev/stdout untouched.
loc -o /dev/stdout | cat > "$o/pipe.csv"; cmp "$o/ref.csv" "$o/pipe.csv"
loc -o /dev/stdout > "$o/redirected.csv"; cmp "$o/ref.csv" "$o/redirected.csv"
test -L /dev/stdout
# A FIFO with a reader: the reader gets the data, the FIFO stays a FIFO.
mkfifo "$o/fifo"
cat "$o/fifo" > "$o/from_fifo.csv" & reader=$!
loc -o "$o/fifo"
wait $reader
cmp "$o/ref.csv" "$o/from_fifo.csv"; test -p "$o/fifo"
# A process substitution (/dev/fd/N of this shell, a pipe).
loc -o >(cat > "$o/procsub.csv"); sleep 0.2; wait
cmp "$o/ref.csv" "$o/procsub.csv"
# A symbolic link stays a link; its target is replaced (a new inode: atomic rename) and nothing is
# left beside either.
mkdir -p "$o/elsewhere"; echo old > "$o/elsewhere/target.csv"
ln -s elsewhere/target.csv "$o/link.csv"
ino_before=$(stat -c %i "$o/elsewhere/target.csv")
loc -o "$o/link.csv"
test -L "$o/link.csv"; test "$(readlink "$o/link.csv")" = elsewhere/target.csv
cmp "$o/ref.csv" "$o/elsewhere/target.csv"
test "$(stat -c %i "$o/elsewhere/target.csv")" != "$ino_before"
test -z "$(find "$o" "$o/elsewhere" -maxdepth 1 -name '.*.csv.*')"
# A chain of links, and a dangling link (its target is created, the link kept).
ln -s link.csv "$o/link2.csv"; echo old > "$o/elsewhere/target.csv"
loc -o "$o/link2.csv"; test -L "$o/link2.csv"; test -L "$o/link.csv"; cmp "$o/ref.csv" "$o/elsewhere/target.csv"
ln -s elsewhere/new.csv "$o/dangling.csv"
loc -o "$o/dangling.csv"; test -L "$o/dangling.csv"; cmp "$o/ref.csv" "$o/elsewhere/new.csv"
# A link to a FIFO is written through.
mkfifo "$o/elsewhere/fifo2"; ln -s elsewhere/fifo2 "$o/fifolink"
cat "$o/fifolink" > "$o/from_fifo2.csv" & reader=$!
loc -o "$o/fifolink"; wait $reader
cmp "$o/ref.csv" "$o/from_fifo2.csv"; test -p "$o/elsewhere/fifo2"; test -L "$o/fifolink"
# A character device made for the test (the null device's numbers; root only): written through, kept.
if mknod "$o/nulldev" c 1 3 2>/dev/null; then
  loc -o "$o/nulldev"; test -c "$o/nulldev"
  loc --report "$o/nulldev" -o "$o/r.csv"; test -c "$o/nulldev"
else
  echo "note: mknod not permitted here; the device case is covered by the FIFO and /dev/stdout cases"
fi
# A folder is refused (exit 4), and a failed run leaves the FIFO's reader nothing.
mkdir "$o/adir"; $expect 4 - 'adir' -- rk-locate --track "$d/track.csv" --camera "$d/camera.json" --turret "$d/turret.csv" -o "$o/adir"
test -d "$o/adir"
echo ok
