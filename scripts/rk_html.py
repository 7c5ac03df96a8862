"""Shared by the trial report page (scripts/rk-report) and rk-nightly's index.html (docs/rk-run.md,
"The report page"): the page's style sheet, escaping, the headline figures of a trial taken from its
out/report.json, its warnings, and the nightly index. Python 3 standard library only (rk-nightly must not
need matplotlib); the pages it makes are self-contained: no script, no font, no style sheet and no image is
fetched from anywhere when they are opened."""
import datetime
import html
import json
import math
import os
import re
import urllib.parse

# One style sheet for both pages, inlined in each (no external CSS).
CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;margin:0;color:#1d232a;
background:#f6f7f9;font-size:14px;line-height:1.4}
header{background:#1f3a5f;color:#fff;padding:12px 24px}
header h1{margin:0;font-size:20px}
header .sub{opacity:.85;font-size:13px}
nav{padding:6px 24px;background:#e6eaf0;font-size:13px}
nav a{margin-right:14px;color:#1f3a5f}
main{padding:8px 24px 40px}
section{background:#fff;border:1px solid #dde2e8;border-radius:6px;margin:14px 0;padding:10px 16px}
h2{font-size:17px;margin:4px 0 8px;color:#1f3a5f}
h3{font-size:15px;margin:12px 0 6px}
table{border-collapse:collapse;margin:6px 0;font-size:13px}
th,td{border:1px solid #dde2e8;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#eef1f5}
td.num{text-align:right;font-variant-numeric:tabular-nums}
td b,.fig .v{white-space:nowrap}
.ok,.done,.up-to-date{color:#17692f;font-weight:600}.warning{color:#9a6200;font-weight:600}
.failed,.locked{color:#b3261e;font-weight:600}.muted{color:#6b7580}.not-started{color:#6b7580;font-weight:600}
.headline{display:flex;flex-wrap:wrap;gap:10px;margin:6px 0}
.fig{display:inline-block;background:#fafbfc;border:1px solid #e3e7ec;border-radius:4px;padding:10px 14px;
min-width:130px}
.fig .v{font-size:20px;font-weight:600}.fig .k{font-size:12px;color:#56606b}
ul.warn li{margin:2px 0}
figure{margin:8px 0}figure svg{max-width:100%;height:auto}
figcaption{font-size:12px;color:#56606b}
pre{background:#f3f4f6;padding:8px;overflow:auto;font-size:12px;max-height:480px}
details summary{cursor:pointer;color:#1f3a5f}
"""

FAILED_RESULTS = ("failed", "locked")


# Angles that wrap — azimuth, yaw, roll, longitude, right ascension: a whole turn apart is the same direction.
# Between two rows more than half a turn apart a figure's line is the wrap (359.9° → 0.1°), not a motion across
# the panel, and is not drawn; the values stay as the CSV has them (the read-out and the axis show them). One rule
# for the static figures (rk-report) and the interactive charts (rk_interactive → scripts/web/rk_plots.js).
_WRAPPING_ANGLE = re.compile(r"(?:^|_)(?:az|yaw|roll|lon|ra)_deg$")
HALF_TURN_DEG = 180.0


def angle_wraps(column):
    """Whether a column is an angle that wraps (its 1σ column is not)."""
    return bool(_WRAPPING_ANGLE.search(column)) and not column.startswith("sigma_")


def wrap_breaks(values):
    """Indices i whose row is more than half a turn from the previous finite row (no row between them is
    finite-less: a missing value already breaks a line)."""
    out, last = [], None
    for i, v in enumerate(values):
        if not (isinstance(v, (int, float)) and math.isfinite(v)):
            last = None
            continue
        if last is not None and abs(v - last) > HALF_TURN_DEG:
            out.append(i)
        last = v
    return out


def cut_at_wraps(breaks, x, *series):
    """x and the series drawn against it (y, its band's edges) with a gap before each row of `breaks`
    (wrap_breaks): x halfway between the two rows, NaN in every series, so that a line through them stops there.
    Lists, in the order given."""
    cut = set(breaks)
    cols = [[] for _ in range(1 + len(series))]
    for i, row in enumerate(zip(x, *series)):
        if i in cut:
            cols[0].append((x[i - 1] + x[i]) / 2)
            for c in cols[1:]:
                c.append(math.nan)
        for c, v in zip(cols, row):
            c.append(v)
    return cols


def esc(x):
    return html.escape("" if x is None else str(x), quote=True)


def num(v, digits=3):
    """A number for a table: integers as they are, others with `digits` significant decimals."""
    if v is None:
        return ""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if v != v:
            return ""
        if v == int(v) and abs(v) < 1e15:
            return "%d" % v
        a = abs(v)
        if a >= 1000 or a < 1e-3:
            return "%.*g" % (digits + 3, v)
        return ("%.*f" % (digits, v)).rstrip("0").rstrip(".") if a >= 1 else "%.*g" % (digits, v)
    return str(v)


def percent(fraction):
    """The one way a fraction is shown on both pages (the browser test looks for this text)."""
    return "%.1f %%" % (100.0 * fraction)


# How deep the pages read JSON. A manifest may carry extra keys of any depth (SPEC.md §6 keeps them, rk-run copies
# them into report.json), but Python's json module and the pages' recursive walks (json.dumps, the quality table)
# recurse once or twice per level, and Python stops at 1000 frames (RecursionError; issue 27 item 9: a 5000-level
# key cost a trial its page and the night its index). rangekit's own reports nest about 10 deep; deeper values are
# shown as NESTED_TOO_DEEP.
MAX_JSON_DEPTH = 100
NESTED_TOO_DEEP = "(nested deeper than %d levels: not shown)" % MAX_JSON_DEPTH
# A JSON string (escapes included) or a bracket: what the depth scan below has to tell apart.
_JSON_TOKEN = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"|[\[\]{}]', re.S)


def _cut_deep(text, limit):
    """(text, n): JSON text with every array or object that opens deeper than `limit` replaced by the string
    NESTED_TOO_DEEP (n of them). One pass over the tokens, no recursion, so any depth is fine."""
    parts, depth, last, start, n = [], 0, 0, None, 0
    for m in _JSON_TOKEN.finditer(text):
        tok = m.group()
        if tok[0] == '"':
            continue
        if tok in "[{":
            depth += 1
            if depth == limit + 1:
                start = m.start()
        else:
            if depth == limit + 1 and start is not None:
                parts += [text[last:start], json.dumps(NESTED_TOO_DEEP)]
                last, start, n = m.end(), None, n + 1
            depth -= 1
    parts.append(text[last:])
    return "".join(parts), n


def loads_bounded(text):
    """(value, n): json.loads(text), except that values nested deeper than MAX_JSON_DEPTH come back as the
    string NESTED_TOO_DEEP, n of them (0 for every ordinary file: the cut is made only when Python's parser gives
    up). ValueError as json.loads for text that is not JSON."""
    try:
        return json.loads(text), 0
    except RecursionError:
        pass
    cut, n = _cut_deep(text, MAX_JSON_DEPTH)
    return json.loads(cut), n


def load_json(path):
    """A JSON file read with loads_bounded, or None when it cannot be read or is not JSON."""
    try:
        with open(path, encoding="utf-8") as f:
            return loads_bounded(f.read())[0]
    except (OSError, ValueError):
        return None


def utc_now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")


def page(title, header_html, nav, body, scripts=""):
    """A whole page: no external resource. `scripts`: inline <script> and <style> elements put at the end of the
    body (the interactive figures, scripts/rk_interactive.py); without them the page has no script at all."""
    links = "".join('<a href="#%s">%s</a>' % (esc(a), esc(t)) for a, t in nav)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">"
            # Forbids every fetch, so that a page that would reach out breaks visibly in any browser; inline
            # scripts only when the page has them.
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
            "style-src 'unsafe-inline'; img-src data:%s\">"
            "<title>%s</title><style>%s</style></head>\n<body><header>%s</header>%s<main>\n%s\n</main>%s</body></html>\n"
            % ("; script-src 'unsafe-inline'" if scripts else "", esc(title), CSS, header_html,
               "<nav>%s</nav>" % links if nav else "", body, scripts))


def step_quality(step):
    q = step.get("quality")
    return q if isinstance(q, dict) else {}


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and v == v


def _figure(label, value, unit, note):
    """(label, value or None, unit, note, text): one headline figure; the text as the pages show it."""
    if not _is_number(value):
        return (label, None, unit, note, "—")
    return (label, value, unit, note, value_text(value, unit))


def value_text(value, unit):
    """A headline figure's value as the pages show it: a fraction as a percentage, else the number and its unit."""
    return percent(value) if unit == "fraction" else ("%s %s" % (num(value), unit)).strip()


def typed_headline(step):
    """[(label, value or None, unit, note, text)] of the "headline" figures of a step's tool report (issue 28 item
    4), or None for a report written before it."""
    tr = step.get("tool_report")
    if not isinstance(tr, dict) or not isinstance(tr.get("headline"), dict):
        return None
    out = []
    for name, f in tr["headline"].items():
        if not isinstance(f, dict):
            continue
        label = ("%s %s" % (step.get("unit", ""), name)).strip()
        out.append(_figure(label, f.get("value"), f.get("unit", ""), f.get("note", "")))
    return out


def headline(report):
    """[(label, value or None, unit, note, text)] of a trial: the figures a person looks at first, each step's tool
    report's "headline" (docs/rk-run.md "The summary contract"); for a report of an older rk, from the step's
    quality record by step kind. The one source of headline_figures (the pages) and headline_values (the
    nightly trend)."""
    out = []
    steps = report.get("steps") if isinstance(report, dict) else None
    for st in steps if isinstance(steps, list) else []:
        if not isinstance(st, dict):
            continue
        if st.get("status", "ok") not in ("ok", "skipped"):  # a failed step's figures are not the trial's
            continue
        typed = typed_headline(st)
        if typed is not None:
            out += typed
            continue
        q = step_quality(st)
        kind, unit = st.get("kind", ""), st.get("unit", "")
        if not q:
            continue
        rows = q.get("rows")
        okf = q.get("ok_fraction")
        if kind == "extract-beacon" and _is_number(okf):
            out.append(_figure("%s tracked frames" % unit, okf, "fraction", "%s of %s frames" % (
                num(q.get("status", {}).get("ok", round(okf * (rows or 0)))), num(rows))))
        elif kind == "locate" and _is_number(q.get("range_coverage")):
            out.append(_figure("%s range coverage" % unit, q["range_coverage"], "fraction", "rows with a range"))
        elif kind == "attitude-oi" and _is_number(q.get("poses")) and q.get("frames"):
            out.append(_figure("%s poses" % unit, q["poses"] / q["frames"], "fraction", "%s of %s frames" % (
                num(q["poses"]), num(q["frames"]))))
        elif kind in ("extract-features", "extract-silhouette", "attitude-cylinder") and _is_number(okf):
            out.append(_figure("%s %s ok" % (unit, kind), okf, "fraction", "%s rows" % num(rows)))
        elif kind.startswith("register") and isinstance(q.get("estimate"), dict):
            for radar, est in sorted(q["estimate"].items()):
                if isinstance(est, dict) and _is_number(est.get("range_m")):
                    sig = q.get("sigma", {}).get(radar, {}) if isinstance(q.get("sigma"), dict) else {}
                    s = sig.get("range_m") if isinstance(sig, dict) else None
                    out.append(_figure("radar %s range bias (%s)" % (radar, kind), est["range_m"], "m",
                                       "1σ %s m" % num(s) if _is_number(s) else ""))
    return out


def headline_figures(report):
    """[(label, value text, note)] of a trial's headline figures, as the pages show them."""
    return [(label, text, note) for label, _, _, note, text in headline(report)]


def headline_values(report):
    """[(label, value, unit)] of a trial's numeric headline figures (the nightly trend)."""
    return [(label, value, unit) for label, value, unit, _, _ in headline(report) if value is not None]


def headline_html(figs):
    if not figs:
        return '<p class="muted">no headline figures (no step reported quality figures)</p>'
    return '<div class="headline">' + "".join(
        '<div class="fig"><div class="v">%s</div><div class="k">%s</div><div class="k">%s</div></div>'
        % (esc(v), esc(k), esc(d)) for k, v, d in figs) + "</div>"


def one_line(text, width=200):
    lines = [ln for ln in str(text or "").splitlines() if ln.strip()]
    line = " ".join(lines[0].split()) if lines else ""
    return line if len(line) <= width else line[:width - 1] + "…"


def index_row(r, root):
    """One trial's row of the index: result, reason, headline figures of TRIAL/out/report.json, page link."""
    d = r.get("dir") or os.path.join(root, r.get("trial", ""))
    rep = load_json(os.path.join(d, "out", "report.json"))
    page_path = os.path.join(d, "out", "report.html")
    # A relative URL, not a path: a folder named "t#3", "a?b" or "100%" would otherwise end the path at its '#'
    # or '?', or be decoded; quote() leaves only the '/' between folders as it is.
    link = esc(urllib.parse.quote(os.path.relpath(page_path, root)))
    result = r.get("result", "failed")
    if os.path.isfile(page_path):
        what = "page" if result not in FAILED_RESULTS else "last good run"
        cell = '<a href="%s">%s</a>' % (link, what)
    else:
        cell = '<span class="muted">no page</span>'
    figs = headline_figures(rep) if isinstance(rep, dict) else []
    figs_html = "<br>".join("%s: <b>%s</b>" % (esc(k), esc(v)) for k, v, _ in figs) or \
        '<span class="muted">—</span>'
    if figs and result in FAILED_RESULTS:
        figs_html = '<span class="muted">last good run:</span><br>' + figs_html
    return ("<tr><td>%s</td><td class=\"%s\">%s</td><td>%s</td><td>%s</td><td class=\"num\">%s</td>"
            "<td class=\"num\">%s / %s</td><td>%s</td></tr>"
            % (esc(r.get("trial")), esc(result), esc(result), esc(one_line(r.get("reason"))), figs_html,
               esc(num(r.get("wall_s"))), esc(r.get("steps_run", 0)), esc(r.get("steps_skipped", 0)), cell))


def night_headlines(summary):
    """{trial: [(label, value, unit)]} of one night's summary (rk-nightly puts each trial's numeric headline
    figures in its row as "headline")."""
    out = {}
    for r in summary.get("trials", []) if isinstance(summary, dict) else []:
        h = r.get("headline") if isinstance(r, dict) else None
        if isinstance(h, list):
            out[r.get("trial", "?")] = [(f.get("label"), f.get("value"), f.get("unit", "")) for f in h
                                        if isinstance(f, dict) and _is_number(f.get("value"))]
    return out


MAX_TREND_PANELS = 8  # headline figures per trial in the trend (the rest are listed in the table only)


def trend_html(summaries):
    """The nightly index's trend: each trial's headline figures against the night they ran, from the summaries of
    the previous nights and this one (oldest first), one small figure per trial and a table of first, last and
    change, so that a slow drift (a camera going out of focus, a turret wearing) shows before it fails."""
    import rk_svg  # noqa: E402 - only the index with a history draws
    nights = []
    for s in summaries:
        t = parse_utc(s.get("started_utc")) if isinstance(s, dict) else None
        if t is not None:
            nights.append((t, night_headlines(s)))
    nights.sort(key=lambda n: n[0])
    if len(nights) < 2:
        return "<p class=\"muted\">A trend needs two nights or more; %d summary so far (kept in ROOT/.rk-nightly/history/).</p>" % len(nights)
    t0 = nights[0][0]
    series = {}  # trial -> label -> ([days], [values], unit)
    for t, by_trial in nights:
        days = (t - t0).total_seconds() / 86400.0
        for trial, figs in by_trial.items():
            for label, value, unit in figs:
                xs, ys, _ = series.setdefault(trial, {}).setdefault(label, ([], [], unit))
                xs.append(days)
                ys.append(value)
    parts = ["<p>%d nights from %s to %s (x: days since the first).</p>" % (
        len(nights), esc(t0.strftime("%Y-%m-%d %H:%M")), esc(nights[-1][0].strftime("%Y-%m-%d %H:%M")))]
    for trial in sorted(series):
        labels = [k for k, v in series[trial].items() if len(v[0]) >= 2]
        if not labels:
            continue
        shown = labels[:MAX_TREND_PANELS]
        fig = rk_svg.Figure(figsize=(7.0, 1.3 * len(shown) + 0.4))
        ax = fig.subplots(len(shown), 1, squeeze=False, sharex=True)
        rows = []
        for k, label in enumerate(labels):
            xs, ys, unit = series[trial][label]
            if k < len(shown):
                ax[k][0].plot(xs, ys, "o-", markersize=3)
                ax[k][0].set_ylabel(label if len(label) <= 28 else "…" + label[-27:])
            first, last = ys[0], ys[-1]
            change = "%+.1f %%" % (100.0 * (last - first) / abs(first)) if first else "—"
            rows.append("<tr><td>%s</td><td class=\"num\">%d</td><td class=\"num\">%s</td><td class=\"num\">%s</td>"
                        "<td class=\"num\">%s</td><td class=\"num\">%s … %s</td></tr>" % (
                            esc(label), len(ys), esc(value_text(first, unit)), esc(value_text(last, unit)),
                            esc(change), esc(value_text(min(ys), unit)), esc(value_text(max(ys), unit))))
        ax[-1][0].set_xlabel("days since the first night")
        ax[0][0].set_title(trial)
        fig.salt = "trend%d" % len(parts)
        parts.append("<h3>%s</h3><figure>%s</figure><table><tr><th>figure</th><th>nights</th><th>first</th>"
                     "<th>last</th><th>change</th><th>range</th></tr>%s</table>" % (
                         esc(trial), fig.to_svg(), "".join(rows)))
    return "".join(parts)


def parse_utc(text):
    """An ISO-8601 UTC time as the summaries write it (rk_batch.utc_now; with or without milliseconds), or None."""
    for f in ("%Y-%m-%dT%H:%M:%S.%fZ", "%Y-%m-%dT%H:%M:%SZ"):
        try:
            return datetime.datetime.strptime(text, f)
        except (TypeError, ValueError):
            pass
    return None


def index_html(summary, root, history=None):
    """(page, not_listed): rk-nightly's ROOT/index.html — every trial, failures first, with its result, a one-line
    reason, its headline figures (from TRIAL/out/report.json) and a link to TRIAL/out/report.html — and the
    [(trial, error)] whose row could not be made (a damaged report.json...): such a row says so, and the other
    trials are listed all the same."""
    trials = list(summary.get("trials", []))
    order = {"failed": 0, "locked": 1, "not-started": 2}
    trials.sort(key=lambda r: (order.get(r.get("result"), 3), r.get("trial", "")))
    counts = summary.get("counts", {})
    rows, not_listed = [], []
    for r in trials:
        try:
            rows.append(index_row(r, root))
        except Exception as e:  # noqa: BLE001 - one trial's row never costs the others theirs
            why = "%s: %s" % (type(e).__name__, e)
            not_listed.append((r.get("trial"), why))
            rows.append("<tr><td>%s</td><td class=\"failed\">row not made</td><td colspan=\"6\">%s</td></tr>"
                        % (esc(r.get("trial")), esc(one_line(why))))
    head = ("<h1>Nightly run: %s</h1><div class=\"sub\">%d trials — %s; started %s, wall %s s; page made %s</div>"
            % (esc(summary.get("root", root)), len(trials),
               esc(", ".join("%s %s" % (v, k.replace("_", " ")) for k, v in counts.items())),
               esc(summary.get("started_utc", "")), esc(num(summary.get("wall_s"))), esc(utc_now())))
    body = ("<section id=\"trials\"><h2>Trials (failures first)</h2><table><tr><th>trial</th><th>result</th>"
            "<th>reason</th><th>headline figures</th><th>wall s</th><th>steps run / skipped</th><th>report</th></tr>"
            + "\n".join(rows) + "</table></section>")
    if history is not None:
        try:
            trend = trend_html(list(history) + [summary])
        except Exception as e:  # noqa: BLE001 - the trend never costs the index
            trend = "<p class=\"warning\">trend not drawn: %s</p>" % esc(one_line("%s: %s" % (type(e).__name__, e)))
        body += "<section id=\"trend\"><h2>Trend of the headline figures</h2>%s</section>" % trend
    return page("rk-nightly: " + os.path.basename(root.rstrip("/")), head, [], body), not_listed
