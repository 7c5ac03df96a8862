#!/usr/bin/env bash
# rk-capture on a really full disk (ENOSPC): a 12 MB tmpfs mounted in a private mount namespace, so
# nothing outside this test sees it. Needs CAP_SYS_ADMIN (root, no container restriction); exits 77
# (ctest: skipped) where that is not allowed. With min_free_mb 0 (no reserve kept for the small
# streams; the reserve itself is tested in tests/capture), frames hit ENOSPC in the middle and are
# cut back; the space a cut-back frame leaves keeps the range log going after the video stopped.
# Exit status 4 (records not written); recover finds the trial readable, frames.csv matching the
# frames on disk.
#   capture_disk_full.sh DATA_DIR        (rk-capture and rk-sim on PATH)
set -eu
d=$1/capture_disk_full
if [ "${RK_IN_NAMESPACE:-}" != 1 ]; then
  rm -rf "$d"; mkdir -p "$d/mnt"
  if ! unshare -m true 2> /dev/null; then echo "no private mount namespace here: skipped"; exit 77; fi
  RK_IN_NAMESPACE=1 exec unshare -m bash "$0" "$@"
fi
mount -t tmpfs -o size=12m tmpfs "$d/mnt" || { echo "cannot mount a tmpfs: skipped"; exit 77; }
cd "$d"
rk-sim device dimetix --link "$d/dls" --duration 40 > /dev/null &
dls=$!
trap 'kill $dls 2> /dev/null || true; umount "$d/mnt" 2> /dev/null || true' EXIT
for i in $(seq 1 100); do [ -e "$d/dls" ] && break; sleep 0.05; done
for min in 0; do
  printf '%s\n' '{"cameras": [{"name": "az", "source": "synthetic:640x512", "fps": 20}],' \
    ' "rangefinder": {"port": "dls", "baud": 115200, "rate_hz": 5}, "segment_s": 2,' \
    " \"min_free_mb\": $min}" > "station$min.json"
  set +e
  rk-capture --config "station$min.json" --out "mnt/t$min" --duration 3 --quiet 2> "err$min"
  rc=$?
  set -e
  cat "err$min"
  [ $rc = 4 ] || { echo "exit status $rc, expected 4"; exit 1; }
  rk-capture recover "mnt/t$min" --quiet
  python3 - "mnt/t$min" "$min" <<'PY'
import csv, json, os, sys
t, min_free = sys.argv[1], int(sys.argv[2])
m = json.load(open(os.path.join(t, "trial.json")))
cam = m["capture"]["streams"]["cameras"]["az"]
def rows(p):
    return [r for r in csv.DictReader(l for l in open(os.path.join(t, p)) if not l.startswith("#"))]
frames, rng = rows("az/frames.csv"), rows("range.csv")
n = 0
for seg in m["cameras"]["az"]["video"]:
    p = os.path.join(t, seg)
    size = os.path.getsize(p) - len(open(p, "rb").readline())
    assert size % (6 + 640 * 512) == 0, (seg, size)  # whole frames only
    n += size // (6 + 640 * 512)
assert n == len(frames) > 15, (n, len(frames))
assert cam["write_failed"] > 0, cam
last_frame, last_range = float(frames[-1]["t_s"]), float(rng[-1]["t_s"])
assert last_range > last_frame + 0.5, (last_frame, last_range)  # range went on after the video stopped
assert any(g["stream"] == "camera:az" and "No space left" in g["reason"] for g in m["capture"]["gaps"])
print("%s: %d frames until the disk was full, %d range rows (the last %.1f s after the last frame)"
      % (t, n, len(rng), last_range - last_frame))
PY
  rm -rf "mnt/t$min"
done
echo ok
