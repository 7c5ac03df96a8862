#!/usr/bin/env python3
"""Scores rk-extract features output against rk-sim attitude truth (truth/points.csv).

usage: attitude_points_stats.py POINTS.csv TRUTH_POINTS.csv [--skip N]

Joins rows by (frame, id). Prints per-coordinate bias / std / RMS of x_px, y_px over the
measured points (status ok or reacquired), the number of identity errors (a measured point
more than 5 px from its own marker's truth: a swap or a wrong blob), and the status counts.
Standard library only.
"""
import csv
import math
import sys


def main():
    args = sys.argv[1:]
    skip = 0
    if "--skip" in args:
        i = args.index("--skip")
        skip = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    truth = {}
    with open(args[1]) as f:
        for r in csv.DictReader(l for l in f if not l.startswith("#")):
            if r["x_px"]:
                truth[(int(r["frame"]), r["id"])] = (float(r["x_px"]), float(r["y_px"]))
    ex, ey, status = [], [], {}
    wrong = 0
    with open(args[0]) as f:
        for r in csv.DictReader(l for l in f if not l.startswith("#")):
            fr = int(r["frame"])
            if fr < skip:
                continue
            status[r["status"]] = status.get(r["status"], 0) + 1
            if r["status"] not in ("ok", "reacquired") or not r["x_px"]:
                continue
            t = truth.get((fr, r["id"]))
            if t is None:
                wrong += 1
                continue
            dx, dy = float(r["x_px"]) - t[0], float(r["y_px"]) - t[1]
            if math.hypot(dx, dy) > 5.0:
                wrong += 1
                continue
            ex.append(dx)
            ey.append(dy)

    def stats(v):
        n = len(v)
        m = sum(v) / n
        s = math.sqrt(sum((x - m) ** 2 for x in v) / max(n - 1, 1))
        r = math.sqrt(sum(x * x for x in v) / n)
        return m, s, r

    if not ex:
        print("no measured points")
        return 1
    mx, sx, rx = stats(ex)
    my, sy, ry = stats(ey)
    print(f"points {len(ex)}  identity errors {wrong}  status {status}")
    print(f"x_px bias {mx:+.4f} std {sx:.4f} rms {rx:.4f}   y_px bias {my:+.4f} std {sy:.4f} rms {ry:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
