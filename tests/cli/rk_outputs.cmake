# Output paths that are not regular files (SPEC.md §2, "Writes are atomic"; docs/conventions.md): a FIFO
# with a reader, symbolic links (to a file, a chain, a dangling one), -o -, /dev/stdout into a pipe and
# into a file, a character device made for the test, rk-plot, rk-sim's and rk-run's folders behind a
# link. No test here writes to the real /dev/null; devnull_after checks that nothing in the suite did.
function(rk_outputs_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; src=$3\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT}
    ${PROJECT_SOURCE_DIR})
endfunction()

# rk-locate (the C++ writer every tool uses): reference output to a regular file, then each kind of path.
rk_outputs_script(rk_outputs_locate [==[
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
]==] REQUIRES locate_data)

# rk-plot (Python writer, scripts/rk_output.py): a link stays a link, a FIFO is written through, -o -.
rk_outputs_script(rk_outputs_plot [==[
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
]==] REQUIRES locate_data)

# Folder outputs behind a link: rk-sim --out and rk-run's out/ keep the link and replace its target.
rk_outputs_script(rk_outputs_folders [==[
o=$data/outputs/folders; rm -rf "$o"; mkdir -p "$o/disk"
mkdir "$o/disk/trial"; ln -s disk/trial "$o/trial"
rk-sim beacon --out "$o/trial" --preset small --duration 0.5 --format png --seed 3 --quiet
test -L "$o/trial"; test -f "$o/disk/trial/trial.json"
rk-sim beacon --out "$o/trial" --force --preset small --duration 0.5 --format png --seed 4 --quiet
test -L "$o/trial"; test -f "$o/disk/trial/trial.json"
test -z "$(find "$o" "$o/disk" -maxdepth 1 -name '.trial*')"
# rk-run: TRIAL/out is a link to a folder on "another disk"; two runs (the second swaps).
mkdir -p "$o/results/out"; ln -s ../../results/out "$o/disk/trial/out"
rk-run "$o/disk/trial" > /dev/null
test -L "$o/disk/trial/out"; test -f "$o/results/out/report.json"
rk-run --force "$o/disk/trial" > /dev/null
test -L "$o/disk/trial/out"; test -f "$o/results/out/report.json"
test -z "$(find "$o/results" "$o/disk/trial" -maxdepth 1 -name 'out.*')"
# rk-nightly's summary through a link (scripts/rk_output.py).
mkdir "$o/sums"; ln -s sums/nightly.json "$o/summary.json"
python3 "$src/scripts/rk-nightly" "$o/disk" --summary "$o/summary.json" --quiet > /dev/null
test -L "$o/summary.json"; test -s "$o/sums/nightly.json"
echo ok
]==])

# The suite never damages the machine: /dev/null is a character device before and after every test
# (every CLI and unit test requires the devnull fixture, so devnull_after runs last).
rk_cli_test(devnull_before COMMAND test -c /dev/null SETUP devnull)
rk_cli_test(devnull_after COMMAND test -c /dev/null)
set_tests_properties(devnull_after PROPERTIES FIXTURES_CLEANUP devnull)
