"""A small SVG plotter for the report page (scripts/rk-report): the few matplotlib calls the page makes
(Figure/Axes: plot, scatter, fill_between, axvspan, errorbar, labels, legend, limits, colorbar), written
straight as SVG text with the Python standard library.

Why not matplotlib itself: importing it and laying out a figure costs about 1 s of CPU per page, as much as
the tools of a short trial together, which would break the nightly target (pages and index ≤ 10 % of the
nightly's wall time, issue 19); this writes a page's figures in a few tens of milliseconds. The figures are
plain vector graphics: lines, bands, shaded spans, markers, ticks at 1-2-5 steps, text as text."""
import math
from html import escape

PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf"]
# viridis at 6 stops, interpolated linearly (scatter colour by time)
VIRIDIS = [(68, 1, 84), (65, 68, 135), (42, 120, 142), (34, 168, 132), (122, 209, 81), (253, 231, 37)]
PT = 72.0  # SVG user units per inch of the figure size
FONT = 10


def viridis(f):
    f = min(1.0, max(0.0, f)) * (len(VIRIDIS) - 1)
    i = min(int(f), len(VIRIDIS) - 2)
    a, b = VIRIDIS[i], VIRIDIS[i + 1]
    w = f - i
    return "#%02x%02x%02x" % tuple(int(round(a[k] + (b[k] - a[k]) * w)) for k in range(3))


def ok(v):
    return v is not None and v == v and not math.isinf(v)


def nice_ticks(lo, hi, n=6):
    if not (ok(lo) and ok(hi)) or hi <= lo:
        return [lo] if ok(lo) else []
    raw = (hi - lo) / max(1, n)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    out, k = [], 0
    while first + k * step <= hi + step * 1e-9 and k < 50:
        out.append(first + k * step)
        k += 1
    return out


def fmt_tick(v, ticks):
    step = abs(ticks[1] - ticks[0]) if len(ticks) > 1 else abs(v) or 1.0
    dec = max(0, -int(math.floor(math.log10(step))) + (1 if step / 10 ** math.floor(math.log10(step)) == 2.5 else 0))
    if abs(v) >= 1e6 or (abs(v) < 1e-4 and v != 0):
        return "%.3g" % v
    s = "%.*f" % (min(dec, 8), v)
    return "0" if s in ("-0", "-0.0") or float(s) == 0 else s


class Line:
    def __init__(self, color):
        self.color = color

    def get_color(self):
        return self.color


class Axes:
    def __init__(self, fig, box):
        self.fig, self.box = fig, box  # box: x, y, w, h in user units
        self.items = []  # (kind, data)
        self.xlabel = self.ylabel = self.title = ""
        self.title_size = FONT + 1
        self.xlim = self.ylim = None
        self.yinvert = False
        self.aspect = None  # display length of a y unit over an x unit ('equal' = 1), None = fill the box
        self.visible = True
        self.legend_on = False
        self.show_xticklabels = True
        self.ncolor = 0
        self.sharex = None

    # -- matplotlib-like calls -----------------------------------------------------------------------
    def _next_color(self):
        c = PALETTE[self.ncolor % len(PALETTE)]
        self.ncolor += 1
        return c

    def plot(self, x, y, fmt="-", label=None, color=None, linestyle=None, markersize=3, **_):
        marker = fmt.strip("-k")[:1] if fmt not in ("-",) else ""
        if fmt.startswith("k"):
            color = color or "#000000"
        c = color or self._next_color()
        dash = "5,3" if linestyle == "--" else None
        line = "-" in fmt and fmt != "." or fmt == "-"
        self.items.append(("line", (list(x), list(y), c, label, dash, line, marker, markersize)))
        return [Line(c)]

    def scatter(self, x, y, c=None, s=4, **_):
        vals = list(c) if c is not None else None
        self.items.append(("scatter", (list(x), list(y), vals)))
        return ("scatter", vals)

    def fill_between(self, x, lo, hi, color=None, alpha=0.25, label=None, **_):
        self.items.append(("band", (list(x), list(lo), list(hi), color or PALETTE[0], alpha, label)))

    def axvspan(self, a, b, color="#d9534f", alpha=0.15, label=None, **_):
        self.items.append(("span", (a, b, color, alpha, label)))

    def errorbar(self, x, y, yerr=None, color="#000000", label=None, **_):
        color = "#000000" if color == "k" else color
        self.items.append(("errorbar", (list(x), list(y), list(yerr or [0] * len(x)), color, label)))

    def annotate(self, text, xy, **_):
        self.items.append(("text", (xy[0], xy[1], str(text))))

    def set_xlabel(self, s):
        self.xlabel = s

    def set_ylabel(self, s):
        self.ylabel = s

    def set_title(self, s, fontsize=None):
        self.title = s
        if fontsize:
            self.title_size = fontsize

    def legend(self, **_):
        self.legend_on = True

    def set_xlim(self, a, b):
        self.xlim = (min(a, b), max(a, b))

    def set_ylim(self, a, b):
        self.ylim = (min(a, b), max(a, b))
        self.yinvert = a > b

    def invert_yaxis(self):
        self.yinvert = True

    def set_aspect(self, how, adjustable=None):
        # matplotlib's meaning: "equal" or a number, the ratio of a y unit's length on the page to an x unit's
        # (1 / cos(latitude) for longitude against latitude); only adjustable="datalim" is drawn.
        self.aspect = 1.0 if how == "equal" else (float(how) if isinstance(how, (int, float)) and how > 0 else None)

    def ticklabel_format(self, **_):
        pass

    def set_visible(self, v):
        self.visible = v

    # -- drawing ----------------------------------------------------------------------------------------
    def data_limits(self):
        xs, ys = [], []
        for kind, d in self.items:
            if kind in ("line", "scatter"):
                xs += [v for v in d[0] if ok(v)]
                ys += [v for v in d[1] if ok(v)]
            elif kind == "band":
                xs += [v for v in d[0] if ok(v)]
                ys += [v for v in d[1] + d[2] if ok(v)]
            elif kind == "errorbar":
                for x, y, e in zip(*d[:3]):
                    if ok(x) and ok(y):
                        xs.append(x)
                        ys += [y - (e or 0), y + (e or 0)]
            elif kind == "text":
                xs.append(d[0])
                ys.append(d[1])
        return xs, ys

    def limits(self):
        xs, ys = self.data_limits()

        def pad(v, lim):
            if lim:
                return lim
            if not v:
                return (0.0, 1.0)
            lo, hi = min(v), max(v)
            if hi == lo:
                d = abs(lo) * 0.01 or 0.5
                return (lo - d, hi + d)
            d = (hi - lo) * 0.04
            return (lo - d, hi + d)
        xl = self.sharex.limits()[0] if self.sharex is not None and self.sharex is not self else pad(xs, self.xlim)
        yl = pad(ys, self.ylim)
        a = self.aspect
        if a and self.xlim and self.ylim and not getattr(self, "_boxed", False):
            x, y, w, h = self.box
            k = min(w / (xl[1] - xl[0]), h / (a * (yl[1] - yl[0])))
            nw, nh = k * (xl[1] - xl[0]), k * a * (yl[1] - yl[0])
            self.box = (x + (w - nw) / 2, y + (h - nh) / 2, nw, nh)
            self._boxed = True
        if a and not self.xlim:
            x, y, w, h = self.box
            sx, sy = (xl[1] - xl[0]) / w, a * (yl[1] - yl[0]) / h
            if sx > sy:
                c, half = (yl[0] + yl[1]) / 2, sx * h / (2 * a)
                yl = (c - half, c + half)
            else:
                c, half = (xl[0] + xl[1]) / 2, sy * w / 2
                xl = (c - half, c + half)
        return xl, yl

    def render(self, out):
        if not self.visible:
            return
        (xa, xb), (ya, yb) = self.limits()  # may narrow the box (equal aspect with both limits set)
        x0, y0, w, h = self.box
        X = lambda v: x0 + (v - xa) / (xb - xa) * w  # noqa: E731
        Y = (lambda v: y0 + (v - ya) / (yb - ya) * h) if self.yinvert else (lambda v: y0 + h - (v - ya) / (yb - ya) * h)  # noqa: E731
        fid = self.fig.clip_id()
        out.append('<clipPath id="%s"><rect x="%.1f" y="%.1f" width="%.1f" height="%.1f"/></clipPath>' % (fid, x0, y0, w, h))
        xt, yt = nice_ticks(xa, xb), nice_ticks(ya, yb, 5)
        grid = "".join("M%.1f %.1fV%.1f" % (X(t), y0, y0 + h) for t in xt) + \
            "".join("M%.1f %.1fH%.1f" % (x0, Y(t), x0 + w) for t in yt)
        out.append('<path d="%s" stroke="#000" stroke-opacity="0.1" stroke-width="0.8" fill="none"/>' % grid)
        body = []
        legend = []
        for kind, d in self.items:
            if kind == "span":
                a, b, color, alpha, label = d
                a, b = max(a, xa), min(b, xb)
                if b > a:
                    body.append('<rect x="%.1f" y="%.1f" width="%.2f" height="%.1f" fill="%s" fill-opacity="%.2f"/>'
                                % (X(a), y0, X(b) - X(a), h, color, alpha))
                if label:
                    legend.append(("rect", color, alpha, label))
        for kind, d in self.items:
            if kind == "band":
                xs, lo, hi, color, alpha, label = d
                segs = _segments([(x, l, u) for x, l, u in zip(xs, lo, hi)], lambda p: ok(p[0]) and ok(p[1]) and ok(p[2]))
                for seg in segs:
                    pts = ["%.1f,%.1f" % (X(p[0]), Y(p[2])) for p in seg] + ["%.1f,%.1f" % (X(p[0]), Y(p[1])) for p in reversed(seg)]
                    body.append('<polygon points="%s" fill="%s" fill-opacity="%.2f"/>' % (" ".join(pts), color, alpha))
                if label:
                    legend.append(("rect", color, alpha, label))
            elif kind == "line":
                xs, ys, color, label, dash, line, marker, ms = d
                segs = _segments(list(zip(xs, ys)), lambda p: ok(p[0]) and ok(p[1]))
                if line:
                    path = "".join("M" + "L".join("%.1f %.1f" % (X(a), Y(b)) for a, b in seg) for seg in segs)
                    body.append('<path d="%s" stroke="%s" stroke-width="1.1" fill="none"%s/>'
                                % (path, color, ' stroke-dasharray="%s"' % dash if dash else ""))
                if marker:
                    r = max(1.0, ms * 0.6)
                    for seg in segs:
                        for a, b in seg:
                            if marker == "^":
                                body.append('<path d="M%.1f %.1fl%.1f %.1fh%.1fz" fill="%s"/>'
                                            % (X(a), Y(b) - r * 2, r * 1.8, r * 3, -r * 3.6, color))
                            else:
                                body.append('<circle cx="%.1f" cy="%.1f" r="%.1f" fill="%s"/>' % (X(a), Y(b), r, color))
                if label:
                    legend.append(("line" if line else ("tri" if marker == "^" else "dot"), color, dash, label))
            elif kind == "scatter":
                xs, ys, vals = d
                vs = [v for v in (vals or []) if ok(v)]
                lo, hi = (min(vs), max(vs)) if vs else (0, 1)
                for i, (a, b) in enumerate(zip(xs, ys)):
                    if ok(a) and ok(b):
                        c = viridis((vals[i] - lo) / (hi - lo)) if vals and ok(vals[i]) and hi > lo else PALETTE[0]
                        body.append('<circle cx="%.1f" cy="%.1f" r="1.6" fill="%s"/>' % (X(a), Y(b), c))
            elif kind == "errorbar":
                xs, ys, es, color, label = d
                for a, b, e in zip(xs, ys, es):
                    if ok(a) and ok(b):
                        body.append('<path d="M%.1f %.1fV%.1fM%.1f %.1fh6M%.1f %.1fh6" stroke="%s" stroke-width="1.1"/>'
                                    '<circle cx="%.1f" cy="%.1f" r="2.2" fill="%s"/>'
                                    % (X(a), Y(b - e), Y(b + e), X(a) - 3, Y(b - e), X(a) - 3, Y(b + e), color, X(a), Y(b), color))
                if label:
                    legend.append(("dot", color, None, label))
            elif kind == "text":
                a, b, t = d
                body.append('<text x="%.1f" y="%.1f" font-size="%d">%s</text>' % (X(a) + 4, Y(b) - 4, FONT - 1, escape(t)))
        out.append('<g clip-path="url(#%s)">%s</g>' % (fid, "".join(body)))
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="none" stroke="#333" stroke-width="0.8"/>'
                   % (x0, y0, w, h))
        ticks = []
        for t in xt:
            ticks.append('<path d="M%.1f %.1fv3.5" stroke="#333" stroke-width="0.8"/>' % (X(t), y0 + h))
            if self.show_xticklabels:
                ticks.append('<text x="%.1f" y="%.1f" text-anchor="middle">%s</text>' % (X(t), y0 + h + 13, fmt_tick(t, xt)))
        for t in yt:
            ticks.append('<path d="M%.1f %.1fh-3.5" stroke="#333" stroke-width="0.8"/>'
                         '<text x="%.1f" y="%.1f" text-anchor="end">%s</text>' % (x0, Y(t), x0 - 5, Y(t) + 3.5, fmt_tick(t, yt)))
        out.append('<g font-size="%d">%s</g>' % (FONT - 1, "".join(ticks)))
        if self.xlabel and self.show_xticklabels:
            out.append('<text x="%.1f" y="%.1f" text-anchor="middle">%s</text>' % (x0 + w / 2, y0 + h + 27, escape(self.xlabel)))
        if self.ylabel:
            out.append('<text transform="translate(%.1f %.1f) rotate(-90)" text-anchor="middle">%s</text>'
                       % (x0 - 48, y0 + h / 2, escape(self.ylabel)))
        if self.title:
            out.append('<text x="%.1f" y="%.1f" text-anchor="middle" font-size="%d">%s</text>'
                       % (x0 + w / 2, y0 - 6, self.title_size + 1, escape(self.title)))
        if self.legend_on and legend:
            pts = []
            for kind, d in self.items:
                if kind in ("line", "scatter"):
                    step = max(1, len(d[0]) // 400)
                    pts += [(X(a), Y(b)) for a, b in zip(d[0][::step], d[1][::step]) if ok(a) and ok(b)]
            self.render_legend(out, legend, pts)

    def render_legend(self, out, entries, pts):
        """In the corner of the axes that covers the fewest drawn points (matplotlib's loc="best", roughly)."""
        x0, y0, w, h = self.box
        lw, lh = 26 + 5.6 * max(len(e[3]) for e in entries), 14 * len(entries) + 6
        corners = [(x0 + 6, y0 + 6), (x0 + w - lw - 6, y0 + 6), (x0 + 6, y0 + h - lh - 6), (x0 + w - lw - 6, y0 + h - lh - 6)]
        lx, ly = min(corners, key=lambda c: sum(1 for px, py in pts if c[0] <= px <= c[0] + lw and c[1] <= py <= c[1] + lh))
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#fff" fill-opacity="0.85" stroke="#ccc"/>'
                   % (lx, ly, lw, lh))
        for k, (kind, color, extra, label) in enumerate(entries):
            y = ly + 13 + 14 * k
            if kind == "rect":
                out.append('<rect x="%.1f" y="%.1f" width="16" height="8" fill="%s" fill-opacity="%.2f"/>'
                           % (lx + 5, y - 7, color, max(extra, 0.25)))
            elif kind == "line":
                out.append('<path d="M%.1f %.1fh16" stroke="%s" stroke-width="1.4"%s/>'
                           % (lx + 5, y - 3, color, ' stroke-dasharray="%s"' % extra if extra else ""))
            elif kind == "tri":
                out.append('<path d="M%.1f %.1fl4 7h-8z" fill="%s"/>' % (lx + 13, y - 9, color))
            else:
                out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (lx + 13, y - 3, color))
            out.append('<text x="%.1f" y="%.1f" font-size="%d">%s</text>' % (lx + 25, y, FONT - 1, escape(label)))


def _segments(points, good):
    segs, cur = [], []
    for p in points:
        if good(p):
            cur.append(p)
        elif cur:
            segs.append(cur)
            cur = []
    if cur:
        segs.append(cur)
    return segs


class Figure:
    LEFT, RIGHT, TOP, BOTTOM = 70.0, 18.0, 26.0, 40.0

    def __init__(self, figsize):
        self.w, self.h = figsize[0] * PT, figsize[1] * PT
        self.axes = []
        self.colorbars = []
        self.salt = "f"
        self._clip = 0

    def clip_id(self):
        self._clip += 1
        return "%s-c%d" % (self.salt, self._clip)

    def subplots(self, rows, cols, squeeze=False, sharex=True):
        gap_x, gap_y = 78.0 if cols > 1 else 0.0, 34.0 if sharex else 52.0
        aw = (self.w - self.LEFT - self.RIGHT - gap_x * (cols - 1)) / cols
        ah = (self.h - self.TOP - self.BOTTOM - gap_y * (rows - 1)) / rows
        grid = [[Axes(self, (self.LEFT + c * (aw + gap_x), self.TOP + r * (ah + gap_y), aw, ah)) for c in range(cols)]
                for r in range(rows)]
        if sharex and rows > 1:
            for c in range(cols):
                for r in range(rows):
                    grid[r][c].sharex = grid[rows - 1][c]
                    grid[r][c].show_xticklabels = r == rows - 1
        self.axes = [a for row in grid for a in row]
        return grid

    def colorbar(self, mappable, ax=None, label=""):
        """Narrows `ax` and puts a vertical colour scale of the scatter's values beside it."""
        vals = [v for v in (mappable[1] or []) if ok(v)]
        x, y, w, h = ax.box
        ax.box = (x, y, w - 58, h)
        self.colorbars.append(((x + w - 44, y, 12, h), (min(vals), max(vals)) if vals else (0, 1), label))

    def to_svg(self):
        # 1.6 px per unit (a 9-inch figure ≈ 1040 px wide); the page's CSS shrinks it to the column (max-width 100 %)
        out = ['<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 %.0f %.0f" width="%.0f" font-family="sans-serif" '
               'font-size="%d">' % (self.w, self.h, self.w * 1.6, FONT), '<rect width="100%" height="100%" fill="#fff"/>']
        for a in self.axes:
            a.render(out)
        for k, ((x, y, w, h), (lo, hi), label) in enumerate(self.colorbars):
            gid = "%s-g%d" % (self.salt, k)
            stops = "".join('<stop offset="%.2f" stop-color="%s"/>' % (i / 5.0, viridis(1 - i / 5.0)) for i in range(6))
            out.append('<defs><linearGradient id="%s" x1="0" y1="0" x2="0" y2="1">%s</linearGradient></defs>'
                       '<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="url(#%s)" stroke="#333" stroke-width="0.6"/>'
                       % (gid, stops, x, y, w, h, gid))
            ticks = nice_ticks(lo, hi, 5)
            for t in ticks:
                ty = y + h - (t - lo) / ((hi - lo) or 1) * h
                out.append('<text x="%.1f" y="%.1f" font-size="%d">%s</text>' % (x + w + 3, ty + 3, FONT - 1, fmt_tick(t, ticks)))
            out.append('<text transform="translate(%.1f %.1f) rotate(90)" text-anchor="middle" font-size="%d">%s</text>'
                       % (x + w + 26, y + h / 2, FONT - 1, escape(label)))
        out.append("</svg>")
        return "".join(out)
