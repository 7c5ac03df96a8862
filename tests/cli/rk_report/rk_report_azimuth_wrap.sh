#!/usr/bin/env bash
# CLI test rk_report_azimuth_wrap: registered, and described, in tests/cli/rk_report.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
# The small trial's page (made by rk_report_page) with its azimuth turned by -31°, so that the target crosses
# north (359.x° → 0.x°) in the middle of a tracked stretch, away from its lost frames.
# And a target that sits on north: its azimuth jitters across it, wrapping between every pair of rows.
t=$data/report/north; rm -rf "$t"; cp -r "$data/report/page" "$t"
j=$data/report/north_jitter; rm -rf "$j"; cp -r "$data/report/page" "$j"
python3 - "$t/out/az/located.csv" "$j/out/az/located.csv" <<'PY'
import sys


def turned(k, az):
    return (az - 31.0) % 360.0


def jittered(k, az):
    return (0.02 if k % 2 else -0.02) % 360.0


for path, turn in ((sys.argv[1], turned), (sys.argv[2], jittered)):
    out, head, k = [], None, 0
    for line in open(path).read().split("\n"):
        if not line or line.startswith("#"):
            out.append(line)
            continue
        f = line.split(",")
        if head is None:
            head = f
        else:
            for c in ("az_deg", "boresight_az_deg"):
                i = head.index(c)
                if f[i]:
                    f[i] = "%.9f" % turn(k, float(f[i]))
            k += 1
        out.append(",".join(f))
    open(path, "w").write("\n".join(out))
PY
rk-report "$t/out" -q
rk-report "$t/out" --static -o "$t/static.html" -q
python3 - "$t" <<'PY'
import re, sys
t = sys.argv[1]
rows = [l.split(",") for l in open(t + "/out/az/located.csv").read().split("\n") if l and not l.startswith("#")]
head, rows = rows[0], rows[1:]
az = [float(r[head.index("az_deg")]) if r[head.index("az_deg")] else None for r in rows]
wraps = sum(1 for a, b in zip(az, az[1:]) if a is not None and b is not None and abs(a - b) > 180)
gaps = sum(1 for a, b in zip(az, az[1:]) if a is not None and b is None)
assert wraps == 1, wraps
# The interactive page says which columns wrap; the static page's azimuth line is cut at the wrap as well as at
# the lost frames (one more piece than without the wrap), the elevation's only at the lost frames.
page = open(t + "/out/report.html").read()
assert 'data-wrap="[&quot;az_deg&quot;]"' in page
static = open(t + "/static.html").read()
i = static.find("azimuth and elevation")
fig = static[static.rfind("<svg", 0, i):static.find("</svg>", i)]
pieces = [m.group(1).count("M") for m in re.finditer(r'<path d="([^"]*)" stroke="#1f77b4"', fig)]
assert pieces == [1 + gaps + wraps, 1 + gaps], (pieces, gaps, wraps)
print("static: az_deg in", pieces[0], "pieces, el_deg in", pieces[1])
PY
# The target on north: every row is beside a wrap, so each is drawn as a point (the static figure's circles), not
# left out with the cut line.
rk-report "$j/out" -q
rk-report "$j/out" --static -o "$j/static.html" -q
python3 - "$j" <<'PY'
import sys
j = sys.argv[1]
rows = [l.split(",") for l in open(j + "/out/az/located.csv").read().split("\n") if l and not l.startswith("#")]
finite = sum(1 for r in rows[1:] if r[rows[0].index("az_deg")])
static = open(j + "/static.html").read()
i = static.find("azimuth and elevation")
fig = static[static.rfind("<svg", 0, i):static.find("</svg>", i)]
dots = fig.count('fill="#1f77b4"/>')
assert dots == finite, (dots, finite)
print("static, target on north:", dots, "points for", finite, "rows")
PY
if ! command -v chromium > /dev/null || ! command -v node > /dev/null; then
  echo "SKIPPED (the static page passed): chromium or node is not installed (scripts/setup.sh --browser)"; exit 77
fi
# In the browser: the panel's wraps are the CSV's and its line and ±1σ band are clipped over each, on the whole
# series and after a zoom and reset (and the page's other checks: no request, read-out against the CSV; the
# first paint under playwright, with its WebGL start, held to 3 s as in rk_report_pages_in_chromium).
node "$src/tests/cli/report_interactive.mjs" "$t/out/report.html" --csv "$t/out/az/located.csv" --group az \
  --column az_deg --wrap --max-fcp-ms 3000
node "$src/tests/cli/report_interactive.mjs" "$j/out/report.html" --csv "$j/out/az/located.csv" --group az \
  --column az_deg --wrap --max-fcp-ms 3000
echo ok
