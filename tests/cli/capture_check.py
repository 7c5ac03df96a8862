#!/usr/bin/env python3
"""Checks every record of a trial written by rk-capture against the device emulators' truth logs.

capture_check.py TRIAL --dls-truth F --ptu-truth F [--source-md5 F] [--cutoff MONO_S] [--state S]
                  [--min-frames N] [--expect-faults]

Truth: the emulators (rk-sim device) log every reply they sent with its CLOCK_MONOTONIC time; the
replayed video's per-frame MD5s (ffmpeg framemd5) are in --source-md5. Checks:
  range.csv    every measurement reply sent before --cutoff is a row, in order, same value/status,
               stamped at arrival (within kArrivalTolS after it was sent); no row that was not sent
  turret.csv   rows are (PP answer, TP answer) pairs of the unit, in order; every pair answered within
               the driver's timeout before --cutoff is a row; az/el from the counts by the mapping
  frames.csv   frame = 0..n-1, t_s and seq increasing; the video as listed in the manifest holds
               exactly n frames; with --source-md5, frame k is bit-identical to source frame seq_k mod N
  faults       with --expect-faults: error replies are rows with their code, the silences are gaps
  all logs     t_s non-decreasing (frames: strictly increasing)
Exit status 0 when every check passes.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

# A reply is stamped when rk-capture's read returns; the emulator logs just before writing it. On a
# loaded 2-core machine a thread may wait for the CPU; 0.2 s bounds that and is still the period of
# the 5 Hz range log.
kArrivalTolS = 0.2
# Angles are printed with 9 decimals.
kAngleTolDeg = 2e-9
# A reply this close to the driver's timeout may or may not be in time, depending on scheduling.
kTimeoutMarginS = 0.05

fails = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        fails.append(what)


def read_csv(path):
    with open(path, newline="") as f:
        lines = [l for l in f if not l.startswith("#")]
    rows = list(csv.DictReader(lines))
    return rows


def read_truth(path):
    out = []
    with open(path) as f:
        next(f)
        for line in f:
            line = line.rstrip("\n")
            a = line.index(",")
            b = line.index(",", a + 1)
            out.append((float(line[:a]), line[a + 1:b], line[b + 1:]))
    return out


def increasing(rows, col, name):
    vals = [float(r[col]) for r in rows]
    bad = [i for i in range(1, len(vals)) if not vals[i] > vals[i - 1]]
    check(not bad, "%s: %s strictly increasing over %d rows" % (name, col, len(vals)))


def nondecreasing(rows, col, name):
    # Two replies read by one read() share their arrival time (SPEC.md §2: rows in non-decreasing t_s).
    vals = [float(r[col]) for r in rows]
    bad = [i for i in range(1, len(vals)) if vals[i] < vals[i - 1]]
    same = sum(1 for i in range(1, len(vals)) if vals[i] == vals[i - 1])
    check(not bad, "%s: %s non-decreasing over %d rows (%d equal pairs)" % (name, col, len(vals), same))


def check_range(trial, truth_path, cutoff):
    rows = read_csv(os.path.join(trial, "range.csv"))
    nondecreasing(rows, "t_s", "range.csv")
    sent = []
    for mono, ev, data in read_truth(truth_path):
        m = re.fullmatch(r"g0[gh]\+(\d{8})", data)
        e = re.fullmatch(r"g0@E(\d{3})", data)
        if ev == "sent" and (m or e):
            sent.append((mono, m.group(1) if m else None, e.group(1) if e else None))
    before = [s for s in sent if s[0] < cutoff]
    check(len(rows) >= len(before), "range.csv: %d rows for %d measurements sent before the cutoff" %
          (len(rows), len(before)))
    check(len(rows) <= len(sent), "range.csv: no more rows (%d) than measurements sent (%d)" % (len(rows), len(sent)))
    bad = 0
    errors = 0
    for i, (mono, dist, code) in enumerate(sent[:len(rows)]):
        r = rows[i]
        arrival = float(r["host_mono_s"])
        ok = 0 <= arrival - mono <= kArrivalTolS
        if dist is not None:
            ok = ok and r["status"] == "0" and r["range_m"] == "%.4f" % (int(dist) / 1e4)
        else:
            errors += 1
            ok = ok and r["status"] == str(int(code)) and r["range_m"] == ""
        if not ok:
            bad += 1
            if bad <= 3:
                print("  row %d: %s vs sent %s at %.6f" % (i, r, (dist, code), mono))
    check(bad == 0, "range.csv: every row is the measurement the device sent, in order (%d error rows)" % errors)
    return errors


def check_turret(trial, truth_path, cutoff, manifest):
    rows = read_csv(os.path.join(trial, "turret.csv"))
    nondecreasing(rows, "t_s", "turret.csv")
    cfg = manifest["capture"]["config"]["turret"]
    timeout = cfg.get("timeout_s", 0.5)
    # The unit answers in order: the n-th reply answers the n-th command it took.
    commands, replies = [], []
    for mono, ev, data in read_truth(truth_path):
        if ev == "received":
            commands.append((mono, data))
        elif ev in ("sent", "dropped", "garbage", "lost"):
            replies.append((mono, ev, data))
    pairs = []  # (pan, tilt, pp_sent, tp_sent, on_time)
    pan = None
    for (cmd_t, cmd), (mono, ev, data) in zip(commands, replies):
        m = re.fullmatch(r"\* (-?\d+)", data)
        good = ev == "sent" and m is not None
        on_time = mono - cmd_t <= timeout - kTimeoutMarginS
        if cmd == "PP":
            pan = (int(m.group(1)), mono, on_time) if good else None
        elif cmd == "TP":
            if pan is not None and good:
                pairs.append((pan[0], int(m.group(1)), pan[1], mono, pan[2] and on_time))
            pan = None
        else:
            pan = None
    # Rows: an in-order subsequence of the unit's answer pairs (a pair answered too late is refused
    # by the driver, never mis-paired), stamped between the two answers.
    k = 0
    matched = set()
    bad = 0
    for i, r in enumerate(rows):
        p_pos, t_pos, mono = int(r["pan_pos"]), int(r["tilt_pos"]), float(r["host_mono_s"])
        while k < len(pairs) and not (pairs[k][0] == p_pos and pairs[k][1] == t_pos and
                                      pairs[k][2] <= mono <= pairs[k][3] + kArrivalTolS):
            k += 1
        if k == len(pairs):
            bad += 1
            if bad <= 3:
                print("  row %d %s is no answer pair of the unit (in order)" % (i, (p_pos, t_pos, mono)))
            k = 0
            continue
        matched.add(k)
        k += 1
    check(bad == 0, "turret.csv: every row (%d) is a (PP, TP) answer pair of the unit, in order" % len(rows))
    expected = [n for n, p in enumerate(pairs) if p[4] and p[3] < cutoff]
    lost = [n for n in expected if n not in matched]
    check(not lost, "turret.csv: all %d pairs answered within the timeout before the cutoff are rows (%d lost)" %
          (len(expected), len(lost)))
    zero, sign = cfg.get("pan_zero_deg", 0.0), cfg.get("pan_sign", 1.0)
    tzero, tsign = cfg.get("tilt_zero_deg", 0.0), cfg.get("tilt_sign", 1.0)
    bad = 0
    for r in rows:
        p, t = int(r["pan_pos"]), int(r["tilt_pos"])
        res_p, res_t = float(r["pan_res_arcsec"]), float(r["tilt_res_arcsec"])
        az = (zero + sign * p * res_p / 3600.0) % 360.0
        el = tzero + tsign * t * res_t / 3600.0
        daz = (float(r["az_deg"]) - az + 180.0) % 360.0 - 180.0
        ok = abs(daz) <= kAngleTolDeg and abs(float(r["el_deg"]) - el) <= kAngleTolDeg
        ok = ok and 0.0 <= float(r["az_deg"]) < 360.0
        bad += 0 if ok else 1
    check(bad == 0, "turret.csv: az/el = the configured mapping of the counts, az in [0, 360)")


def framemd5(path):
    out = subprocess.run(["ffmpeg", "-v", "error", "-nostdin", "-i", path, "-map", "0:v:0", "-pix_fmt", "gray",
                          "-f", "framemd5", "-"], check=True, capture_output=True, text=True).stdout
    return [l.split(",")[-1].strip() for l in out.splitlines() if l and not l.startswith("#")]


def check_frames(trial, manifest, source_md5):
    for name, cam in manifest["cameras"].items():
        rows = read_csv(os.path.join(trial, cam["frames"]))
        check([int(r["frame"]) for r in rows] == list(range(len(rows))), "%s: frame counts 0..%d" % (name, len(rows) - 1))
        increasing(rows, "t_s", name + "/frames.csv")
        increasing(rows, "seq", name + "/frames.csv")
        md5 = []
        for seg in cam["video"]:
            md5 += framemd5(os.path.join(trial, seg))
        check(len(md5) == len(rows), "%s: %d frames in %d segment(s), %d rows" % (name, len(md5), len(cam["video"]),
                                                                             len(rows)))
        if source_md5:
            n = len(source_md5)
            same = sum(1 for r, h in zip(rows, md5) if source_md5[int(r["seq"]) % n] == h)
            check(same == len(rows), "%s: %d of %d frames bit-identical to the source frame their row names" %
                  (name, same, len(rows)))
        drops = sum(1 for a, b in zip(rows, rows[1:]) if int(b["seq"]) != int(a["seq"]) + 1)
        print("     %s: %d frames, %d jump(s) in seq (frames dropped before the disk)" % (name, len(rows), drops))
        return len(rows)
    return 0


def main():
    ap = argparse.ArgumentParser(allow_abbrev=False)
    ap.add_argument("trial")
    ap.add_argument("--dls-truth", required=True)
    ap.add_argument("--ptu-truth", required=True)
    ap.add_argument("--source-md5", default=None)
    ap.add_argument("--cutoff", type=float, default=math.inf)
    ap.add_argument("--state", default=None)
    ap.add_argument("--min-frames", type=int, default=0)
    ap.add_argument("--expect-faults", action="store_true")
    a = ap.parse_args()
    manifest = json.load(open(os.path.join(a.trial, "trial.json")))
    if a.state:
        check(manifest["capture"]["state"] == a.state, "manifest state %s" % manifest["capture"]["state"])
    source_md5 = None
    if a.source_md5:
        with open(a.source_md5) as f:
            source_md5 = [l.split(",")[-1].strip() for l in f if l.strip() and not l.startswith("#")]
    errors = check_range(a.trial, a.dls_truth, a.cutoff)
    check_turret(a.trial, a.ptu_truth, a.cutoff, manifest)
    n = check_frames(a.trial, manifest, source_md5)
    check(n >= a.min_frames, "frames: %d >= %d" % (n, a.min_frames))
    streams = sorted({g["stream"] for g in manifest["capture"]["gaps"]})
    if a.expect_faults:
        check(errors > 0, "range.csv: the injected error replies are rows with their code")
        check({"range", "turret"} <= set(streams), "gaps recorded for the silent devices: %s" % streams)
    else:
        check(not streams, "no gaps (%s)" % streams)
    print("%d check(s) failed" % len(fails) if fails else "all checks passed")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
