"""The report page's interactive figures (issue 34; docs/rk-run.md "The report page"): rk-report's side of
scripts/web/rk_plots.js, which the build bundles with uPlot and three.js into rk_report_assets/rk_plots.js.

rk-report asks this module for a chart (time series, one panel per column, at full resolution) or a 3-D view of a
trajectory; each returns the <div> the script fills, and registers the table's columns it needs. `payload()`
gives what goes once at the end of the page: the data (every table's t_s as float64, each column and its 1σ as
float32, the status codes, the lost / invalid / predicted spans; base64 in one JSON element), uPlot's style sheet
and the bundled script. Nothing is fetched: the page's Content-Security-Policy allows inline scripts only.
"""
import array
import base64
import json
import math
import os

ASSETS = "rk_report_assets"
SCRIPT, STYLE = "rk_plots.js", "uPlot.min.css"


def find_assets(script_path):
    """The folder holding the bundled script beside rk-report (build/apps or an installed bin/), or None."""
    here = os.path.dirname(os.path.realpath(script_path))
    for d in (os.path.join(here, ASSETS), os.path.join(os.path.dirname(script_path), ASSETS)):
        if os.path.isfile(os.path.join(d, SCRIPT)) and os.path.isfile(os.path.join(d, STYLE)):
            return d
    return None


def _b64(typecode, values):
    a = array.array(typecode, values)
    if a.itemsize > 1 and array.array("H", [1]).tobytes()[0] != 1:
        a.byteswap()  # the page reads little-endian typed arrays
    return base64.b64encode(a.tobytes()).decode("ascii")


def _attr(v):
    return (json.dumps(v) if not isinstance(v, str) else v).replace("&", "&amp;").replace("'", "&#39;") \
        .replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


class Interactive:
    STATUS_NAMES = ["ok", "reacquired", "predicted", "lost", "invalid", "other"]

    def __init__(self, assets_dir, bad_spans):
        self.assets = assets_dir
        self.bad_spans = bad_spans  # rk-report's: (table, max_spans) → [[t0, t1], ...]
        self.tables = {}  # id(table) → (key, table, set of columns)

    def _register(self, tab, cols):
        k = id(tab)
        if k not in self.tables:
            self.tables[k] = ("T%d" % (len(self.tables) + 1), tab, set())
        key, _, need = self.tables[k]
        for c in cols:
            need.add(c)
            s = tab.sigma_of(c)
            if s:
                need.add(s)
        return key

    def chart(self, tab, cols, group, title):
        """A chart with one panel per column against t_s (only columns with a finite value)."""
        cols = [c for c in cols if tab.has(c) and any(v == v for v in tab.num(c))]
        if not cols or not tab.has("t_s"):
            return ""
        key = self._register(tab, cols)
        bands = [c for c in cols if tab.sigma_of(c)]
        return ("<figure><div class=\"rk-chart\" data-table=\"%s\" data-cols=\"%s\" data-group=\"%s\"></div>"
                "<figcaption>%s — drag to zoom, double-click to reset (every panel of %s follows); the line under "
                "each panel reads the value%s at the cursor%s</figcaption></figure>" % (
                    key, _attr(cols), _attr(group), _html(title), _html(group),
                    " and its 1σ" if bands else "", "; shaded band: ±1σ" if bands else ""))

    def view3d(self, tab, x, y, z, group, title, stations=(), colour="time"):
        """The path in 3-D (x, y, z: ENU columns in metres) with the stations [(name, e, n, u)] and, at the time
        cursor of `group`'s charts, the target and the stations' lines of sight to it."""
        if not tab.has(x, y, z, "t_s"):
            return ""
        key = self._register(tab, [x, y, z])
        st = [{"name": n, "e": e, "n": nn, "u": u} for n, e, nn, u in stations
              if all(isinstance(v, (int, float)) and math.isfinite(v) for v in (e, nn, u))]
        return ("<figure><div class=\"rk-3d\" data-table=\"%s\" data-x=\"%s\" data-y=\"%s\" data-z=\"%s\" "
                "data-colour=\"%s\" data-group=\"%s\" data-stations=\"%s\"></div><figcaption>%s — drag to orbit, "
                "wheel to zoom, right-drag to pan; coloured by %s; grid: the ground plane (u = 0); %s</figcaption>"
                "</figure>" % (key, x, y, z, colour, _attr(group), _attr(st), _html(title),
                               "time (dark: start, yellow: end)" if colour == "time" else "status",
                               "black: the stations; red: the target and the lines of sight at the charts' cursor"
                               if st else "red: the target at the charts' cursor"))

    def payload(self):
        if not self.tables:
            return ""
        tables = {}
        for key, tab, need in self.tables.values():
            t = tab.num("t_s")
            entry = {"n": tab.n, "t": _b64("d", t), "cols": {}, "sigma": {}, "bad": self.bad_spans(tab, 5000)}
            for c in sorted(need):
                if c == "t_s":
                    continue
                owner = next((o for o in need if tab.sigma_of(o) == c), None)
                (entry["sigma"] if owner else entry["cols"])[owner or c] = _b64("f", tab.num(c))
            if tab.has("status"):
                names = self.STATUS_NAMES
                codes = [names.index(s) if s in names else len(names) - 1 for s in tab.text("status")]
                entry["status"] = {"names": names, "codes": _b64("B", codes)}
            tables[key] = entry
        data = json.dumps({"tables": tables}, separators=(",", ":")).replace("</", "<\\/")
        with open(os.path.join(self.assets, STYLE), encoding="utf-8") as f:
            style = f.read()
        with open(os.path.join(self.assets, SCRIPT), encoding="utf-8") as f:
            script = f.read().replace("</script", "<\\/script")
        return ("<style>%s .rk-readout{font:12px monospace;color:#333;min-height:1.3em;margin:0 0 6px 70px}"
                ".rk-chart,.rk-3d{width:100%%;max-width:1100px}</style>"
                "<script type=\"application/json\" id=\"rk-data\">%s</script><script>%s</script>" % (style, data, script))


def _html(s):
    return str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
