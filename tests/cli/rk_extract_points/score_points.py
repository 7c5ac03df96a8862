#!/usr/bin/env python3
"""Scores an rk-extract points track against rk-sim points' truth (tests/cli/rk_extract_points.cmake).

Usage: score_points.py POINTS.csv TRUTH.csv REPORT.json [--lookalike]
Checks, per id: one row per frame; no measured (ok/reacquired) row while the marker is hidden (truth visible 0,
occlusion 1); measured rows within their method's error bound and, pooled, RMS error / RMS σ in [0.5, 2]
(the tests' looser band: tens of rows, not the benchmark's thousands); after each hidden span the marker is
measured again within 2 frames of its return; the report's per-point counts match the file.
With --lookalike: no measured row of any id lies within 2 px of the look-alike while it is shown.
"""
import csv
import json
import math
import sys

ERROR_MAX = {"quadrant": 0.1, "circle": 0.1, "centroid-bright": 0.15, "centroid-dark": 0.15, "correlation": 0.2}
REACQUIRE_FRAMES = 2
RATIO_LO, RATIO_HI = 0.5, 2.0


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    pts, truth, report = rows(sys.argv[1]), rows(sys.argv[2]), json.load(open(sys.argv[3]))
    lookalike = "--lookalike" in sys.argv
    t = {(r["frame"], r["id"]): r for r in truth}
    methods = {p["id"]: p["method"] for p in report["points"]}
    fail = []
    by_id = {}
    for r in pts:
        by_id.setdefault(r["id"], []).append(r)
    frames = {r["frame"] for r in truth}
    e2 = s2 = 0.0
    for pid, rs in by_id.items():
        if len(rs) != len(frames):
            fail.append(f"{pid}: {len(rs)} rows for {len(frames)} frames")
        hidden_until = None
        for r in rs:
            tr = t[(r["frame"], pid)]
            measured = r["status"] in ("ok", "reacquired")
            seen = tr["visible"] == "1"
            if not seen and float(tr["occlusion"]) >= 0.999 and measured:
                fail.append(f"{pid} frame {r['frame']}: measured while hidden")
            if not seen:
                hidden_until = int(r["frame"])
                continue
            if not measured:
                if hidden_until is None or int(r["frame"]) > hidden_until + REACQUIRE_FRAMES:
                    fail.append(f"{pid} frame {r['frame']}: visible but {r['status']}")
                continue
            ex, ey = float(r["x_px"]) - float(tr["x_px"]), float(r["y_px"]) - float(tr["y_px"])
            if math.hypot(ex, ey) > ERROR_MAX[methods[pid]]:
                fail.append(f"{pid} frame {r['frame']}: error {math.hypot(ex, ey):.3f} px")
            e2 += ex * ex + ey * ey
            s2 += float(r["sigma_x_px"]) ** 2 + float(r["sigma_y_px"]) ** 2
    ratio = math.sqrt(e2 / s2) if s2 > 0 else float("nan")
    print(f"RMS error / RMS sigma = {ratio:.2f}")
    if not RATIO_LO <= ratio <= RATIO_HI:
        fail.append(f"sigma not honest: ratio {ratio:.2f}")
    for p in report["points"]:
        n = sum(1 for r in by_id[p["id"]] if r["status"] == "ok")
        if p["status_counts"]["ok"] != n:
            fail.append(f"{p['id']}: report says {p['status_counts']['ok']} ok rows, the file {n}")
    if lookalike:
        shown = [r for r in truth if r["id"] == "lookalike" and r["visible"] == "1"]
        if not shown:
            fail.append("the look-alike is never shown")
        for la in shown:
            for r in pts:
                if r["frame"] == la["frame"] and r["status"] in ("ok", "reacquired") and math.hypot(
                        float(r["x_px"]) - float(la["x_px"]), float(r["y_px"]) - float(la["y_px"])) < 2.0:
                    fail.append(f"{r['id']} frame {r['frame']}: on the look-alike")
    for f in fail[:30]:
        print("FAIL:", f)
    sys.exit(1 if fail else 0)


main()
