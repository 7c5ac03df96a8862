#!/usr/bin/env bash
# CLI test rk_run_disk_full: registered, and described, in tests/cli/rk_safety.cmake. A really full disk:
# a small tmpfs mounted in a private mount namespace, so nothing outside this test sees it. Needs
# CAP_SYS_ADMIN (root, no container restriction); exits 77 (ctest: skipped) where that is not allowed.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/safety/diskfull
if [ "${RK_IN_NAMESPACE:-}" != 1 ]; then
  rm -rf "$d"; mkdir -p "$d/mnt"
  if ! unshare -m true 2> /dev/null; then echo "no private mount namespace here: skipped"; exit 77; fi
  RK_IN_NAMESPACE=1 exec unshare -m bash "$0" "$@"
fi
. "$src/tests/cli/rk_run/lib.sh"
mount -t tmpfs -o size=48m tmpfs "$d/mnt" || { echo "cannot mount a tmpfs: skipped"; exit 77; }
trap 'umount "$d/mnt" 2> /dev/null || true' EXIT
t=$d/mnt/trial
fresh "$t"
rk-run "$t" --no-plots -q
test "$(json "$t/last-run.json" 'd["result"]')" = done
# fill PAGES: the file system full but for PAGES pages of 4 KiB.
fill() {
  rm -f "$d/mnt/fill" "$d/mnt/pad"
  [ "$1" = 0 ] || dd if=/dev/zero of="$d/mnt/pad" bs=4096 count="$1" status=none
  dd if=/dev/zero of="$d/mnt/fill" bs=4096 status=none 2> /dev/null || true
  rm -f "$d/mnt/pad"
}
# full_run ERRFILE: rk-run --force on the full disk must exit 4, and last-run.json (if still there) must say
# failed, never an earlier "done".
full_run() {
  set +e; rk-run "$t" --no-plots --force 2> "$1"; rc=$?; set -e
  cat "$1"
  [ $rc = 4 ] || { echo "FAIL: exit $rc, expected 4"; exit 1; }
  if [ -e "$t/last-run.json" ]; then
    r=$(json "$t/last-run.json" 'd["result"]')
    [ "$r" = failed ] || { echo "FAIL: last-run.json says '$r' after a failed run"; exit 1; }
  fi
}
# Item 6: the disk is full from the start: last-run.json is cut down in place to a 'failed' stub (or removed).
fill 0
full_run "$d/full.err"
grep -q 'last-run.json' "$d/full.err" || { echo "FAIL: stderr does not say last-run.json was not written"; exit 1; }
# Item 11: room for rk-run's own small files but not for a step's product. The error names the tool's own
# last error line (No space left on device), although its log could not be written.
fill 3
full_run "$d/step.err"
grep -q 'rk-[a-z]*: error: .*No space left on device' "$d/step.err" || { echo "FAIL: the tool's own error line is not reported"; exit 1; }
# With room again, the next run finds the out/ that the failed runs left as it was.
rm -f "$d/mnt/fill"
rk-run "$t" --no-plots -q
test "$(json "$t/last-run.json" 'd["result"]')" = up-to-date
echo ok
