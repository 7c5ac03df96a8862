#!/usr/bin/python3
"""Recordings for the rk-import CLI tests (tests/cli/rk_import.cmake), written into OUT:
  beacon.mraw + beacon.cihx   the 60 frames of rk_extract's beacon.mkv (8-bit, 160x120) as a Photron file at 20 fps
  gaps.cine                   6 frames, time block at 0, 1, 2, 5, 4, 5 ms after 2023-11-14T22:13:20Z at 1 kHz
                              (a gap of 3 intervals at frame 3, a step back at frame 4), IRIG-synchronised
  truncated.cine              gaps.cine without its last 10 bytes
  count.mraw + count.cihx     a header that counts 3 frames for a file of 2
  depth10.mraw + .cihx        an unknown bit depth (10)
  cam/seg_000.y4m, seg_001.y4m, frames.csv   an rk-capture camera folder (host times from 100 s, 2 segments of 3)
Usage: make_recordings.py OUT BEACON_MKV
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "fuzz"))
import make_camera_seeds as seeds  # noqa: E402

out, mkv = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)


def put(name, data):
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)


raw = subprocess.run(["ffmpeg", "-v", "error", "-nostdin", "-i", mkv, "-f", "rawvideo", "-pix_fmt", "gray", "-"],
                     check=True, capture_output=True).stdout
frames = len(raw) // (160 * 120)
put("beacon.mraw", raw)
put("beacon.cihx", seeds.cihx(160, 120, 8, frames).replace(b"<startFrame>5</startFrame>", b"<startFrame>0</startFrame>")
    .replace(b"<recordRate>30000</recordRate>", b"<recordRate>20</recordRate>"))

t0 = 1700000000
stamps = [(t0 << 32) | (round(ms * 1e-3 * 2**32) & ~3) for ms in (0, 1, 2, 5, 4, 5)]
gaps = seeds.cine(8, 4, 16, 0, stamp_list=stamps)
put("gaps.cine", gaps)
put("truncated.cine", gaps[:-10])

put("count.mraw", seeds.mraw(6, 4, 12, 2))
put("count.cihx", seeds.cihx(6, 4, 12, 3))
put("depth10.mraw", bytes(6 * 4 * 2 * 10 // 8))
put("depth10.cihx", seeds.cihx(6, 4, 10, 2))

os.makedirs(os.path.join(out, "cam"), exist_ok=True)
y = seeds.y4m(8, 4, 8, 3)
put("cam/seg_000.y4m", y)
put("cam/seg_001.y4m", y)
rows = ["frame,t_s,host_mono_s,host_real_s,seq,segment"]
for k in range(6):
    rows.append("%d,%.6f,%.6f,%.6f,%d,%d" % (k, 100 + 0.05 * k + (0.02 if k == 4 else 0), 5 + 0.05 * k, 1.7e9 + k, k, k // 3))
put("cam/frames.csv", ("\n".join(rows) + "\n").encode())
