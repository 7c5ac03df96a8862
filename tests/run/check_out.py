#!/usr/bin/env python3
"""Checks that trial folders hold no half-written out/: for each TRIAL given, out/ is either absent
(--allow-missing) or complete: report.json parses, every product it lists exists with the recorded
size and SHA-256, and no out.tmp.* / out.old.* is left when --no-temporaries is given.
  check_out.py [--allow-missing] [--no-temporaries] [--require-result done,up-to-date] TRIAL...
Prints one line per trial; exit 1 on any problem."""
import glob
import hashlib
import json
import os
import sys


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def check(trial, allow_missing, no_temps):
    out = os.path.join(trial, "out")
    problems = []
    if no_temps:
        left = glob.glob(os.path.join(trial, "out.tmp.*")) + glob.glob(os.path.join(trial, "out.old.*"))
        if left:
            problems.append("temporaries left: %s" % [os.path.basename(x) for x in left])
    if not os.path.isdir(out):
        if not allow_missing:
            problems.append("no out/")
        return "absent", problems
    try:
        rep = json.load(open(os.path.join(out, "report.json")))
    except (OSError, ValueError) as e:
        return "broken", problems + ["out/report.json unreadable: %s" % e]
    n = 0
    for st in rep.get("steps", []):
        if st.get("status") not in ("ok", "skipped", "warning"):
            continue
        for o in st.get("outputs", []):
            p = os.path.join(out, o["path"])
            n += 1
            if not os.path.isfile(p):
                problems.append("%s: missing" % o["path"])
            elif os.path.getsize(p) != o["bytes"] or sha256(p) != o["sha256"]:
                problems.append("%s: differs from report.json" % o["path"])
    if n == 0:
        problems.append("report.json lists no product")
    return "complete (%d products)" % n, problems


def main(argv):
    allow_missing = "--allow-missing" in argv
    no_temps = "--no-temporaries" in argv
    trials = [a for a in argv if not a.startswith("--")]
    bad = 0
    for t in trials:
        state, problems = check(t, allow_missing, no_temps)
        print("%s: %s%s" % (t, state, "; " + "; ".join(problems) if problems else ""))
        bad += bool(problems)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
