#!/usr/bin/env bash
# Reading recordings at the speed of the disk (issue 29): `rk-extract beacon --decode-only` (every frame
# read, unpacked, demosaiced where Bayer, handed to the detector's loop) on a 12-bit packed Photron MRAW, a
# 12-bit packed mono CINE, a 10-bit packed Bayer CINE and rk-capture's 8-bit y4m, each against
#   dd if=FILE of=/dev/null bs=FRAME_BYTES
# on the same file from the page cache (the floor: one copy out of the page cache). Ratios from the same run,
# median of REPEATS runs each, files warmed into the page cache first. Also the full `rk-extract beacon`
# (detector included) on the y4m. Prints a Markdown table (also OUT/summary.md) for docs/benchmarks.md.
#   bench/video_read_bench.sh [OUT]      needs a Release build in build/ (scripts/setup.sh)
# Environment: FRAMES (default 200) frames of W x H (default 2448x2048), REPEATS (default 5).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${RK_BIN:-$ROOT/build/apps}
OUT=${1:-/tmp/rk-video-read-bench}
FRAMES=${FRAMES:-200}
W=${W:-2448}
H=${H:-2048}
REPEATS=${REPEATS:-5}
mkdir -p "$OUT"
S=$OUT/summary.md
: > "$S"
say() { echo "$*" | tee -a "$S"; }

# The recordings: random samples (the reader's cost does not depend on them), headers by make_camera_seeds'
# writers (tests/fuzz/make_camera_seeds.py), data from /dev/urandom.
/usr/bin/python3 - "$OUT" "$FRAMES" "$W" "$H" "$ROOT" <<'PY'
import os, struct, sys
out, n, w, h, root = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
sys.path.insert(0, os.path.join(root, "tests", "fuzz"))
import make_camera_seeds as seeds
def rnd(nbytes):
    return os.urandom(nbytes)
frame12 = w * h * 3 // 2
with open(os.path.join(out, "rec.cihx"), "wb") as f:
    f.write(seeds.cihx(w, h, 12, n))
with open(os.path.join(out, "rec.mraw"), "wb") as f:
    for _ in range(n):
        f.write(rnd(frame12))
def cine(name, compression, file_compression, cfa, frame_bytes):
    # Header, bitmap header and setup as make_camera_seeds.cine writes them, then n offsets and images.
    setup_len = 1600
    off_setup, off_offsets = 84, 84 + setup_len
    hdr = struct.pack("<HHHHiIiIIIIII", 0x4943, 44, file_compression, 1, 0, n, 0, n, 44, off_setup, off_offsets, 0, 1700000000)
    bmp = struct.pack("<IiiHHIIiiII", 40, w, h, 1, 16, compression, frame_bytes, 0, 0, 0, 0)
    setup = bytearray(setup_len)
    struct.pack_into("<HH", setup, 140, 0x5453, setup_len)
    struct.pack_into("<I", setup, 768, 1000)
    struct.pack_into("<I", setup, 808, cfa)
    struct.pack_into("<I", setup, 896, 12)
    with open(os.path.join(out, name), "wb") as f:
        f.write(hdr + bmp + bytes(setup))
        at = off_offsets + 8 * n
        for i in range(n):
            f.write(struct.pack("<Q", at + i * (8 + frame_bytes)))
        for i in range(n):
            f.write(struct.pack("<II", 8, frame_bytes) + rnd(frame_bytes))
cine("rec12.cine", 1024, 0, 0, frame12)
cine("rec10_bayer.cine", 256, 2, 3, w * h * 10 // 8)
with open(os.path.join(out, "rec.y4m"), "wb") as f:
    f.write(b"YUV4MPEG2 W%d H%d F20:1 Ip A1:1 Cmono\n" % (w, h))
    for _ in range(n):
        f.write(b"FRAME\n" + rnd(w * h))
PY

. "$ROOT/bench/lib.sh"  # median, timed

say "## Reading recordings (issue 29) — $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
say ""
say "$FRAMES frames of ${W}x${H}, from the page cache, median of $REPEATS runs; \`bench/video_read_bench.sh\` (Release build)."
say ""
say "| recording | file MB | dd bs=frame (s) | writing the frames (s) | rk-extract beacon --decode-only (s) | ratio to dd | ratio to dd + writing |"
say "|---|---|---|---|---|---|---|"
# "writing the frames": dd if=/dev/zero into a buffer of one delivered frame (FRAMES of them) — the cost of
# writing the 16-bit frames alone; a reader of a packed file cannot do less than read it and write them.
row() {  # name file stored_frame_bytes delivered_frame_bytes
  local name=$1 file=$2 fb=$3 ob=$4
  cat "$file" > /dev/null
  local mb dd wr dec
  mb=$(( $(stat -c %s "$file") / 1000000 ))
  dd=$(timed dd if="$file" of=/dev/null bs="$fb")
  wr=$(timed dd if=/dev/zero of=/dev/null bs="$ob" count="$FRAMES")
  dec=$(timed "$B/rk-extract" beacon --video "$file" --decode-only --quiet)
  say "| $name | $mb | $dd | $wr | $dec | $(awk -v a="$dec" -v b="$dd" 'BEGIN {printf "%.2f", a / b}') | $(awk -v a="$dec" -v b="$dd" -v c="$wr" 'BEGIN {printf "%.2f", a / (b + c)}') |"
}
row "Photron MRAW 12-bit packed" "$OUT/rec.mraw" $((W * H * 3 / 2)) $((W * H * 2))
row "Phantom CINE 12-bit packed mono" "$OUT/rec12.cine" $((W * H * 3 / 2)) $((W * H * 2))
row "Phantom CINE 10-bit packed Bayer (demosaiced)" "$OUT/rec10_bayer.cine" $((W * H * 10 / 8)) $((W * H * 2))
row "rk-capture y4m 8-bit" "$OUT/rec.y4m" $((W * H)) $((W * H))
say ""
cat "$OUT/rec.y4m" > /dev/null
full=$(timed "$B/rk-extract" beacon --video "$OUT/rec.y4m" -o "$OUT/track.csv" --quiet)
dd=$(timed dd if="$OUT/rec.y4m" of=/dev/null bs=$((W * H)))
say "Full \`rk-extract beacon\` on the y4m (detector on random frames, its own times): $full s, $(awk -v a="$full" -v b="$dd" 'BEGIN {printf "%.2f", a / b}') x dd."

# Extraction itself on a real scene: rk-sim beacon at W x H (FRAMES frames: FRAMES/20 s at 20 fps), its 8-bit
# frames written as a 12-bit packed MRAW (value x 16), then the whole `rk-extract beacon` (detection, tracking,
# sub-pixel fit, σ, the CSV) against dd of that file. Random frames (above) are a detector's worst case.
"$B/rk-sim" beacon -o "$OUT/beacon_sim" --force --width "$W" --height "$H" --fps 20 \
  --duration "$(awk -v n="$FRAMES" 'BEGIN {print n / 20}')" --quiet
ffmpeg -v error -nostdin -i "$OUT/beacon_sim/az/video.mkv" -f rawvideo -pix_fmt gray - | /usr/bin/python3 -c '
import sys, numpy as np
w, h, out = int(sys.argv[1]), int(sys.argv[2]), open(sys.argv[3], "wb")
while True:
    b = sys.stdin.buffer.read(w * h)
    if len(b) < w * h:
        break
    v = np.frombuffer(b, np.uint8).astype(np.uint16) * 16
    a, c = v[0::2], v[1::2]
    p = np.empty((a.size, 3), np.uint8)
    p[:, 0], p[:, 1], p[:, 2] = a >> 4, ((a & 15) << 4) | (c >> 8), c & 255
    out.write(p.tobytes())
' "$W" "$H" "$OUT/beacon.mraw"
/usr/bin/python3 -c 'import os, sys; sys.path.insert(0, os.path.join(sys.argv[1], "tests", "fuzz")); import make_camera_seeds as s
open(sys.argv[2], "wb").write(s.cihx(int(sys.argv[3]), int(sys.argv[4]), 12, int(sys.argv[5])))' "$ROOT" "$OUT/beacon.cihx" "$W" "$H" "$FRAMES"
cat "$OUT/beacon.mraw" > /dev/null
full=$(timed "$B/rk-extract" beacon --video "$OUT/beacon.mraw" -o "$OUT/beacon.csv" --quiet)
dec=$(timed "$B/rk-extract" beacon --video "$OUT/beacon.mraw" --decode-only --quiet)
dd=$(timed dd if="$OUT/beacon.mraw" of=/dev/null bs=$((W * H * 3 / 2)))
say "Full \`rk-extract beacon\` on rk-sim beacon's scene as a 12-bit packed MRAW ($(grep -c ',ok,' "$OUT/beacon.csv") of $FRAMES rows ok): $full s, $(awk -v a="$full" -v b="$dd" 'BEGIN {printf "%.2f", a / b}') x dd ($dd s); decoding alone $dec s."
