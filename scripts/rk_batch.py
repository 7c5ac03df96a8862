"""Shared code of rk-nightly and rk-slurm (docs/rk-run.md): finding trials, finding rk-run,
running it with the kernel's parent-death signal, and the summary (JSON + text table) of many rk-run
reports. Python 3 standard library only."""
import datetime
import os
import shutil
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import rk_html  # noqa: E402
import rk_output  # noqa: E402

# Results of one trial, as rk-run's --report says them (and NOT_STARTED: an interrupted batch never started its
# rk-run), and how a summary counts them.
DONE, UP_TO_DATE, LOCKED, FAILED, PLANNED = "done", "up-to-date", "locked", "failed", "planned"
NOT_STARTED = "not-started"
PAGE_WARNING = "report page not made: "  # how rk-run's report_page_warning starts (lib/run/runner.cc)
COUNT_KEYS = {DONE: "done", UP_TO_DATE: "up_to_date", LOCKED: "skipped_locked", FAILED: "failed",
              PLANNED: "planned", NOT_STARTED: "not_started"}
# Counted only when they occur, so that an ordinary night's counts keep their four keys.
OPTIONAL_COUNTS = {PLANNED: "planned", NOT_STARTED: "not_started"}


def utc_now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"


def find_trials(root):
    """(trials, not_followed): every folder under root holding a trial.json (its trial.json path), sorted, and
    [(path relative to root, reason)] of the folders that were not searched although they might hold trials.

    A trial folder is not searched further; hidden folders and rk-run's out/, out.tmp.*, out.old.* are skipped.
    Symbolic links to folders are followed — a trial kept on another disk and linked under ROOT is one of ROOT's
    trials — after the folders themselves, and every folder is searched once, by its first path: a link to a
    folder already searched (a second path to a trial, a link back up the tree) is not followed, nor is a link
    that leads nowhere or a folder that cannot be read; those are the not_followed, for the caller to say."""
    found, not_followed, links = [], [], []
    searched = {os.path.realpath(root): root}  # real path -> the path it was searched by

    def rel(path):
        r = os.path.relpath(path, root)
        return "ROOT" if r == "." else r

    def search(top):
        stack = [top]
        while stack:
            folder = stack.pop()
            try:
                entries = sorted(os.scandir(folder), key=lambda e: e.name)
            except OSError as e:
                not_followed.append((rel(folder), "cannot be read: %s" % e.strerror))
                continue
            if any(e.name == "trial.json" for e in entries):
                found.append(os.path.join(folder, "trial.json"))
                continue
            subs = []
            for e in entries:
                if e.name.startswith(".") or e.name == "out" or e.name.startswith(("out.tmp.", "out.old.")):
                    continue
                if e.is_symlink():
                    if not os.path.exists(e.path):  # a disk not mounted?
                        not_followed.append((rel(e.path), "symbolic link to %s, which does not exist"
                                             % os.readlink(e.path)))
                    elif e.is_dir():
                        links.append(e.path)
                elif e.is_dir(follow_symlinks=False):
                    searched.setdefault(os.path.realpath(e.path), e.path)
                    subs.append(e.path)
            stack.extend(reversed(subs))

    search(root)
    while links:  # each link once the folders that hold it are searched; links found behind it join the queue
        link = links.pop(0)
        real = os.path.realpath(link)
        if real in searched:
            not_followed.append((rel(link), "the same folder as %s, searched once" % rel(searched[real])))
            continue
        searched[real] = link
        search(link)
    return sorted(found), not_followed


def find_rk_run(explicit):
    """--rk-run PATH, else $RK_RUN, else rk-run on PATH, else build/apps/rk-run of this source tree."""
    for cand in (explicit, os.environ.get("RK_RUN")):
        if cand:
            return os.path.abspath(cand) if os.sep in cand else (shutil.which(cand) or cand)
    on_path = shutil.which("rk-run")
    if on_path:
        return on_path
    here = os.path.dirname(os.path.abspath(__file__))
    for cand in (os.path.join(here, "rk-run"), os.path.join(here, "..", "build", "apps", "rk-run")):
        if os.access(cand, os.X_OK):
            return os.path.abspath(cand)
    return None


def die_with_parent():
    """preexec_fn: the child gets SIGKILL when this process dies (kill -9 included), so no rk-run
    outlives the batch that started it; rk-run does the same for its tools."""
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        PR_SET_PDEATHSIG = 1
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except Exception:  # not Linux: children merely outlive us
        pass


def write_atomic(path, text):
    """Summaries are written like every other output (scripts/rk_output.py, SPEC.md §2)."""
    rk_output.write_output(path, text)


def trial_label(manifest, root):
    """The trial's folder relative to ROOT: unique, unlike the manifest's name."""
    rel = os.path.relpath(os.path.dirname(os.path.abspath(manifest)), root)
    return os.path.basename(os.path.abspath(root)) if rel == "." else rel


def trial_record(manifest, report_path, exit_code, wall_s, extra_reason=None, root=None):
    """One row of the summary from rk-run's --report (which may be missing if rk-run was killed)."""
    rec = {"trial": trial_label(manifest, root) if root else os.path.dirname(os.path.abspath(manifest)),
           "dir": os.path.dirname(os.path.abspath(manifest)), "manifest": manifest,
           "name": os.path.basename(os.path.dirname(os.path.abspath(manifest))),
           "exit_code": exit_code, "wall_s": round(wall_s, 3) if wall_s is not None else None,
           "result": FAILED, "reason": None, "steps_run": 0, "steps_skipped": 0, "tool_time_s": 0.0,
           "tool_cpu_s": 0.0}
    rep = rk_html.load_json(report_path) if report_path else None
    if not isinstance(rep, dict):
        rep = None
    if rep is not None:
        rec["name"] = rep.get("trial") or rec["name"]
        rec["result"] = rep.get("result", FAILED)
        counts = rep.get("counts", {})
        rec["steps_run"] = counts.get("run", 0)
        rec["steps_skipped"] = counts.get("skipped", 0)
        rec["warnings"] = counts.get("warnings", 0)
        rec["tool_time_s"] = rep.get("tool_time_s", 0.0) or 0.0
        rec["tool_cpu_s"] = rep.get("tool_cpu_s", 0.0) or 0.0
        if rec["wall_s"] is None:
            rec["wall_s"] = rep.get("wall_s")
        rec["started_utc"] = rep.get("started_utc")
        rec["finished_utc"] = rep.get("finished_utc")
        if rec["result"] == FAILED:
            rec["reason"] = rep.get("error") or "failed"
        elif rec["result"] == LOCKED:
            rec["reason"] = rep.get("error") or "locked by another run"
        elif rec["result"] == UP_TO_DATE:
            rec["reason"] = "up to date"
        elif rec["result"] == PLANNED:
            rec["reason"] = "would run %d step(s)" % rec["steps_run"] if rec["steps_run"] else "up to date"
        elif rec.get("warnings"):
            rec["reason"] = "%d warning(s): see the trial's last-run.json" % rec["warnings"]
        if rep.get("report_page_warning"):  # rk-run's own verdict stays: the products are good, the page is not
            why = rk_html.one_line(rep["report_page_warning"])
            rec["page_not_made"] = why[len(PAGE_WARNING):] if why.startswith(PAGE_WARNING) else why
            if rec["result"] not in (FAILED, LOCKED):
                rec["reason"] = PAGE_WARNING + rec["page_not_made"]
        if exit_code not in (None, 0) and rec["result"] not in (FAILED, LOCKED):
            rec["result"], rec["reason"] = FAILED, "rk-run exited with code %s" % exit_code
    else:
        if exit_code is None:
            why = extra_reason or "not run"
        elif exit_code < 0:
            why = "rk-run killed by signal %d" % -exit_code
        else:
            why = "rk-run exited with code %d and wrote no report" % exit_code
        rec["reason"] = extra_reason or why
    return rec


def summarize(records, meta):
    """The summary JSON: meta (tool, root, times, cores...) + counts + per-trial rows + timing figures."""
    s = dict(meta)
    counts = {v: 0 for k, v in COUNT_KEYS.items() if k not in OPTIONAL_COUNTS}
    for result, key in OPTIONAL_COUNTS.items():
        if any(r["result"] == result for r in records):
            counts[key] = 0
    for r in records:
        counts[COUNT_KEYS.get(r["result"], "failed")] += 1
    s["counts"] = counts
    s["trials_total"] = len(records)
    tool = sum(r.get("tool_time_s") or 0.0 for r in records)
    cpu = sum(r.get("tool_cpu_s") or 0.0 for r in records)
    s["tool_time_s"] = round(tool, 3)
    s["tool_cpu_s"] = round(cpu, 3)
    cores = meta.get("cores_used") or 1
    wall = meta.get("wall_s")
    if tool > 0 and wall:
        s["ideal_wall_s"] = round(tool / cores, 3)
        s["wall_over_ideal"] = round(wall / (tool / cores), 4)
    s["trials"] = records
    s["pages_not_made"] = [{"trial": r["trial"], "reason": r["page_not_made"]} for r in records
                           if r.get("page_not_made")]
    return s


def add_page_not_made(summary, trial, reason):
    """A page that could not be made after the summary was: a row of rk-nightly's index, or the index itself."""
    summary.setdefault("pages_not_made", []).append({"trial": trial, "reason": rk_html.one_line(reason)})


def text_table(summary):
    c = summary["counts"]
    lines = []
    head = "%s %s: %d trials: %d done, %d up to date, %d skipped (locked), %d failed" % (
        summary.get("tool", "rk-batch"), summary.get("root", ""), summary["trials_total"], c["done"],
        c["up_to_date"], c["skipped_locked"], c["failed"])
    if "not_started" in c:
        head += ", %d not started" % c["not_started"]
    if "planned" in c:
        head += " (dry run: %d with steps to run; steps column = would run/up to date)" % sum(
            1 for r in summary["trials"] if r["result"] == PLANNED and r.get("steps_run"))
    lines.append(head)
    if summary.get("wall_s") is not None:
        extra = ""
        if "wall_over_ideal" in summary:
            extra = "; ideal %.1f s (tools / %s cores), ratio %.3f" % (
                summary["ideal_wall_s"], summary.get("cores_used") or 1, summary["wall_over_ideal"])
        lines.append("wall %.1f s, tools %.1f s (cpu %.1f s)%s" % (summary["wall_s"], summary["tool_time_s"],
                                                                  summary["tool_cpu_s"], extra))
    w = max([5] + [len(r["trial"]) for r in summary["trials"]])
    lines.append("%-*s  %-10s %8s %6s  %s" % (w, "trial", "result", "time_s", "steps", "reason"))
    for r in summary["trials"]:
        t = "%.2f" % r["wall_s"] if r.get("wall_s") is not None else ""
        steps = "%d/%d" % (r.get("steps_run", 0), r.get("steps_skipped", 0))
        reason = (r.get("reason") or "").replace("\n", " ")
        lines.append("%-*s  %-10s %8s %6s  %s" % (w, r["trial"], r["result"], t, steps, reason))
    for p in summary.get("pages_not_made", []):
        lines.append("page not made: %s: %s" % (p["trial"], p["reason"]))
    for p in summary.get("not_followed", []):
        lines.append("not searched: %s: %s" % (p["path"], p["reason"]))
    return "\n".join(lines) + "\n"


def any_failed(summary):
    """Exit code 1 of rk-nightly and rk-slurm: a trial failed, or a page (a trial's report page, rk-nightly's
    index or a row of it) could not be made."""
    return summary["counts"]["failed"] > 0 or bool(summary.get("pages_not_made"))


class Usage(Exception):
    pass


def error_exit(tool, code, message):
    sys.stderr.write("%s: error: %s\n" % (tool, message))
    sys.exit(code)
