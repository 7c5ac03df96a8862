#!/usr/bin/env python3
"""Tracking figures of a beacon track against rk-sim truth (bench/beacon_bench.sh uses it).

beacon_track_stats.py TRACK.csv TRUTH_BEACON.csv [--lock-px 3] [--skip-frames N]

Joins on `frame` and prints one JSON object:
  visible            frames where the truth says the beacon is visible
  tracked_fraction   visible frames with status ok or reacquired and a position within --lock-px of truth
  ok_fraction        visible frames with status ok
  false_frames       frames with a position farther than --lock-px from truth, or a position while the
                     beacon is not visible (a lock on a distractor or on noise)
  reacquire_delays   per occlusion: frames from the first visible frame to the first good measurement
                     (0 = measured on the very first frame the beacon is back)
  x/y error          mean, std, rms (px) over good frames after --skip-frames
"""
import argparse, csv, json, math, sys


def read(path):
    with open(path, newline="") as f:
        lines = [l for l in f if not l.lstrip().startswith("#") and l.strip()]
    return list(csv.DictReader(lines))


def num(s):
    return float(s) if s not in ("", None) else None


def stats(v):
    if not v:
        return None
    n = len(v)
    m = sum(v) / n
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (n - 1)) if n > 1 else 0.0
    return {"n": n, "mean": m, "std": sd, "rms": math.sqrt(sum(x * x for x in v) / n), "max_abs": max(abs(x) for x in v)}


def main():
    ap = argparse.ArgumentParser(allow_abbrev=False)
    ap.add_argument("track")
    ap.add_argument("truth")
    ap.add_argument("--lock-px", type=float, default=3.0)
    ap.add_argument("--skip-frames", type=int, default=0)
    a = ap.parse_args()
    track = {int(r["frame"]): r for r in read(a.track)}
    truth = {int(r["frame"]): r for r in read(a.truth)}
    visible = good = ok = false = 0
    ex, ey = [], []
    delays, in_gap, gap_end, waiting = [], False, None, False
    for f in sorted(truth):
        t = truth[f]
        vis = t.get("visible", "1") not in ("0", "", "false")
        r = track.get(f)
        x, y = (num(r["x_px"]), num(r["y_px"])) if r else (None, None)
        st = r["status"] if r else "missing"
        has = x is not None and y is not None
        if not vis:
            in_gap = True
            if has:
                false += 1
            continue
        visible += 1
        if in_gap:
            in_gap, gap_end, waiting = False, f, True
        xt, yt = num(t["x_px"]), num(t["y_px"])
        d = math.hypot(x - xt, y - yt) if has else None
        if has and d > a.lock_px:
            false += 1
        is_good = has and d <= a.lock_px and st in ("ok", "reacquired")
        if is_good:
            good += 1
            if f >= a.skip_frames:
                ex.append(x - xt)
                ey.append(y - yt)
            if waiting:
                delays.append(f - gap_end)
                waiting = False
        if st == "ok" and is_good:
            ok += 1
    if waiting:
        delays.append(None)
    out = {
        "frames": len(truth), "visible": visible,
        "tracked_fraction": good / visible if visible else None,
        "ok_fraction": ok / visible if visible else None,
        "false_frames": false, "reacquire_delays": delays,
        "x_error_px": stats(ex), "y_error_px": stats(ey),
    }
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
