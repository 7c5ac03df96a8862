"""The report page's interactive figures (issue 34; docs/rk-run.md "The report page"): rk-report's side of
scripts/web/rk_plots.js, which the build bundles with uPlot and three.js into rk_report_assets/rk_plots.js.

rk-report asks this module for a chart (time series, one panel per column, at full resolution) or a 3-D view of a
trajectory; each returns the <div> the script fills, and registers the table's columns it needs. `payload()`
gives what goes once at the end of the page: the data (every table's t_s, each column and its 1σ, the status
codes — each quantised, differenced and compressed, `encode` below —, the lost / invalid / predicted spans; in
one JSON element), uPlot's style sheet and the bundled script. Nothing is fetched: the page's Content-Security-Policy allows inline scripts only.
"""
import array
import base64
import json
import math
import os
import sys
import zlib

import rk_html

# Debian python3-numpy (with python3-matplotlib) encodes a long series 20× faster, to the same bytes; it is
# imported only for one (importing it costs ≈ 70 ms, a third of a short trial's page).
NUMPY_FROM_ROWS = 20000
_numpy = []


def numpy_or_none():
    if not _numpy:
        try:
            import numpy
            _numpy.append(numpy)
        except ImportError:
            _numpy.append(None)
    return _numpy[0]

ASSETS = "rk_report_assets"
SCRIPT, STYLE = "rk_plots.js", "uPlot.min.css"


def find_assets(script_path):
    """The folder holding the bundled script beside rk-report (build/apps or an installed bin/), or None."""
    here = os.path.dirname(os.path.realpath(script_path))
    for d in (os.path.join(here, ASSETS), os.path.join(os.path.dirname(script_path), ASSETS)):
        if os.path.isfile(os.path.join(d, SCRIPT)) and os.path.isfile(os.path.join(d, STYLE)):
            return d
    return None


# A series on the page: quantised to a power of ten (1e-9 s for t_s; else 1e-7 of the series' largest magnitude:
# float32's precision, far below any 1σ), differenced, as little-endian int32 deltas, zlib-compressed (the browser
# inflates them with DecompressionStream), base64. A null row is the delta INT32_MIN (the value stays). About
# 1.5 bytes a row for a smooth series against 5.3 for float32 in base64: what keeps an hour at 20 Hz in a
# page of a few MB.
NULL_DELTA = -2 ** 31


def encode(values, quantum=None, use_numpy=None):
    """The series' dict, or None when a jump between two rows does not fit an int32 (then float64). use_numpy:
    True / False, or None: for a series of NUMPY_FROM_ROWS rows or more, where numpy is installed."""
    n = len(values)
    if use_numpy is None:
        use_numpy = n >= NUMPY_FROM_ROWS
    np = numpy_or_none() if use_numpy else None
    if np is not None:
        v = np.asarray(values, dtype=np.float64)
        fin = np.isfinite(v)
        if not fin.any():
            return _packed(1, 0, n, np.full(n, NULL_DELTA, dtype="<i4").tobytes())
        if quantum is None:
            big = float(np.abs(v[fin]).max())
            quantum = 10.0 ** (math.floor(math.log10(big)) - 7) if big > 0 else 1.0
        k = np.rint(v[fin] / quantum).astype(np.int64)
        d = np.diff(k, prepend=k[0])
        if d.size and (d.min() <= NULL_DELTA or d.max() >= 2 ** 31):
            return None
        deltas = np.full(n, NULL_DELTA, dtype="<i4")
        deltas[fin] = d
        return _packed(quantum, int(k[0]), n, deltas.tobytes())
    # Without numpy: the same, a row at a time.
    inf = float("inf")
    if quantum is None:
        big = max((abs(x) for x in values if x == x and abs(x) != inf), default=None)
        if big is None:
            return _packed(1, 0, n, _i32([NULL_DELTA] * n))
        quantum = 10.0 ** (math.floor(math.log10(big)) - 7) if big > 0 else 1.0
    ks = [round(x / quantum) if x == x and abs(x) != inf else None for x in values]
    k0 = next((k for k in ks if k is not None), 0)
    deltas, last = [], k0
    for k in ks:
        if k is None:
            deltas.append(NULL_DELTA)
            continue
        if not NULL_DELTA < k - last < 2 ** 31:
            return None
        deltas.append(k - last)
        last = k
    return _packed(quantum, k0, n, _i32(deltas))


def _little_endian(a):
    """An array's bytes, little-endian (what the page's Int32Array / Float64Array read)."""
    if sys.byteorder != "little":
        a.byteswap()
    return a.tobytes()


def _i32(ints):
    return _little_endian(array.array("i", ints))


def _packed(quantum, k0, n, raw):
    return {"q": quantum, "k0": k0, "n": n, "z": base64.b64encode(zlib.compress(raw, 6)).decode("ascii")}


def encode_f64(values):
    raw = _little_endian(array.array("d", values))
    return {"f64": base64.b64encode(zlib.compress(raw, 6)).decode("ascii"), "n": len(values)}


def series(values, quantum=None):
    return encode(values, quantum) or encode_f64(values)


def _attr(v):
    """An attribute's value: text as it is, anything else as JSON, escaped (rk_html.esc)."""
    return rk_html.esc(v if isinstance(v, str) else json.dumps(v))


class Interactive:
    STATUS_NAMES = ["ok", "reacquired", "predicted", "lost", "invalid", "other"]

    def __init__(self, assets_dir, bad_spans):
        self.assets = assets_dir
        self.bad_spans = bad_spans  # rk-report's: (table, max_spans) → [[t0, t1], ...]
        self.tables = {}  # id(table) → (key, table, set of columns)

    def _register(self, tab, cols, with_sigma=True):
        k = id(tab)
        if k not in self.tables:
            self.tables[k] = ("T%d" % (len(self.tables) + 1), tab, {})
        key, _, need = self.tables[k]
        for c in cols:
            need.setdefault(c, None)
            s = tab.sigma_of(c) if with_sigma else None
            if s:
                need[c] = s
        return key

    def chart(self, tab, cols, group, title):
        """A chart with one panel per column against t_s (only columns with a finite value)."""
        cols = [c for c in cols if tab.has(c) and any(v == v for v in tab.num(c))]
        if not cols or not tab.has("t_s"):
            return ""
        key = self._register(tab, cols)
        bands = [c for c in cols if tab.sigma_of(c)]
        wrap = [c for c in cols if rk_html.angle_wraps(c)]
        return ("<figure><div class=\"rk-chart\" data-table=\"%s\" data-cols=\"%s\" data-group=\"%s\"%s></div>"
                "<figcaption>%s — drag to zoom, double-click to reset (every panel of %s follows); the line under "
                "each panel reads the value%s at the cursor%s%s</figcaption></figure>" % (
                    key, _attr(cols), _attr(group), " data-wrap=\"%s\"" % _attr(wrap) if wrap else "",
                    rk_html.esc(title), rk_html.esc(group), " and its 1σ" if bands else "",
                    "; shaded band: ±1σ" if bands else "",
                    "; %s: no line across the wrap (a jump of more than %g° between rows)" % (
                        ", ".join(wrap), rk_html.HALF_TURN_DEG) if wrap else ""))

    def view3d(self, tab, x, y, z, group, title, stations=(), colour="time"):
        """The path in 3-D (x, y, z: ENU columns in metres) with the stations [(name, e, n, u)] and, at the time
        cursor of `group`'s charts, the target and the stations' lines of sight to it."""
        if not tab.has(x, y, z, "t_s"):
            return ""
        key = self._register(tab, [x, y, z], with_sigma=False)
        st = [{"name": n, "e": e, "n": nn, "u": u} for n, e, nn, u in stations
              if all(isinstance(v, (int, float)) and math.isfinite(v) for v in (e, nn, u))]
        return ("<figure><div class=\"rk-3d\" data-table=\"%s\" data-x=\"%s\" data-y=\"%s\" data-z=\"%s\" "
                "data-colour=\"%s\" data-group=\"%s\" data-stations=\"%s\"></div><figcaption>%s — drag to orbit, "
                "wheel to zoom, right-drag to pan; coloured by %s; grid: the ground plane (u = 0); %s</figcaption>"
                "</figure>" % (key, x, y, z, colour, _attr(group), _attr(st), rk_html.esc(title),
                               "time (dark: start, yellow: end; or by status: green ok, blue reacquired, "
                               "orange predicted, grey lost, red invalid)" if colour == "time" else "status",
                               "black: the stations; red: the target and the lines of sight at the charts' cursor"
                               if st else "red: the target at the charts' cursor"))

    def payload(self):
        if not self.tables:
            return ""
        tables = {}
        for key, tab, need in self.tables.values():
            entry = {"n": tab.n, "t": series(tab.num("t_s"), 1e-9), "cols": {}, "sigma": {},
                     "bad": self.bad_spans(tab, 5000)}
            for c, s in sorted(need.items()):
                if c == "t_s":
                    continue
                entry["cols"][c] = series(tab.num(c))
                if s:
                    entry["sigma"][c] = series(tab.num(s))
            if tab.has("status"):
                names = self.STATUS_NAMES
                codes = [names.index(s) if s in names else len(names) - 1 for s in tab.text("status")]
                entry["status"] = {"names": names, "codes": series(codes, 1)}
            tables[key] = entry
        data = json.dumps({"tables": tables}, separators=(",", ":")).replace("</", "<\\/")
        with open(os.path.join(self.assets, STYLE), encoding="utf-8") as f:
            style = f.read()
        with open(os.path.join(self.assets, SCRIPT), encoding="utf-8") as f:
            script = f.read().replace("</script", "<\\/script")
        return ("<style>%s .rk-readout{font:12px monospace;color:#333;min-height:1.3em;margin:0 0 6px 70px}"
                ".rk-chart,.rk-3d{width:100%%;max-width:1100px}</style>"
                "<script type=\"application/json\" id=\"rk-data\">%s</script><script>%s</script>" % (style, data, script))

