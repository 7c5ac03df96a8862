#!/usr/bin/env bash
# CLI test rk_report_page: registered, and described, in tests/cli/rk_report.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
t=$data/report/page; fresh "$t"
rk-run "$t" > "$data/report/page.out"
p=$t/out/report.html
test -s "$p" || { echo "no out/report.html"; exit 1; }
check_out --no-temporaries "$t"
python3 - "$t" <<'PY'
import json, re, sys
t = sys.argv[1]
page = open(t + "/out/report.html").read()
rep = json.load(open(t + "/out/report.json"))
# Self-contained: nothing for a browser to fetch. Only in-page anchors; the SVG namespaces are names, not fetches;
# scripts inline (the interactive charts), the page's CSP forbidding every fetch.
for bad in ("<script src", "<link", "<iframe", "<img src=\"http", "@import", "url(http"):
    assert bad not in page, bad
assert "default-src 'none'; style-src 'unsafe-inline'; img-src data:; script-src 'unsafe-inline'\"" in page
refs = re.findall(r'(?:src|href)="([^"]*)"', page)
assert all(r.startswith("#") or r.startswith("data:") for r in refs), [r for r in refs if not r.startswith("#")][:5]
assert page.count("<svg") >= 2, page.count("<svg")          # the track in the image and the plan view at least
assert page.count('class="rk-chart"') >= 4, page.count('class="rk-chart"')  # x/y, az/el, range, height
assert page.count('class="rk-3d"') >= 1                      # the located target's 3-D view
assert page.count('id="rk-data"') == 1
ex = [s for s in rep["steps"] if s["id"] == "az/extract-beacon"][0]
pct = "%.1f %%" % (100 * ex["quality"]["ok_fraction"])
assert pct in page, pct
for step in rep["steps"]:
    assert step["id"] in page, step["id"]
assert rep["tools"]["rk-locate"]["version"] in page
assert "lost" in page                                          # the occluded frames are a warning
print("page ok:", len(page), "bytes,", page.count("<svg"), "figures, tracked", pct)
PY
# Up to date: the page is not made again; gone: it is made again, and out/ stays the same folder.
before=$(stat -c %Y.%i "$p"); ino=$(stat -c %i "$t/out")
rk-run "$t" | grep -q up-to-date
test "$(stat -c %Y.%i "$p")" = "$before"
rm "$p"; rk-run "$t" > /dev/null; test -s "$p"; test "$(stat -c %i "$t/out")" = "$ino"
# --no-plots: no page for a new out/.
n=$data/report/noplots; fresh "$n"; rk-run "$n" --no-plots > /dev/null
test ! -e "$n/out/report.html"
# rk-report failing is a warning: exit 0, the reason in last-run.json, out/ complete.
w=$data/report/warn; fresh "$w"; mkdir -p "$data/report/bin"
printf '#!/bin/sh\necho "rk-report: error: broken on purpose" >&2\nexit 4\n' > "$data/report/bin/rk-report"
chmod +x "$data/report/bin/rk-report"
rk-run "$w" --bin "$data/report/bin" > /dev/null
json "$w/last-run.json" 'd["report_page_warning"]' | grep -q 'broken on purpose'
test "$(json "$w/last-run.json" 'd["result"]')" = done
check_out --no-temporaries "$w"
# rk-report by hand: usage and data errors.
set +e
rk-report "$data/report/nowhere" 2> "$data/report/e1"; rc1=$?
echo '{"tool": "rk-locate"}' > "$data/report/bin/report.json"; rk-report "$data/report/bin" 2> "$data/report/e2"; rc2=$?
set -e
test "$rc1" = 4; grep -q '^rk-report: error: .*report.json: cannot read' "$data/report/e1"
test "$rc2" = 3; grep -q 'not an rk-run report' "$data/report/e2"
rk-report "$t/out" --matplotlib -o "$data/report/mpl.html" --quiet   # the same figures drawn by matplotlib
test "$(grep -o '<svg' "$data/report/mpl.html" | wc -l)" = "$(grep -o '<svg' "$p" | wc -l)"
# --static: every figure an SVG, no script at all (the page of before issue 34), the CSP without scripts.
rk-report "$t/out" --static -o "$data/report/static.html" --quiet
if grep -q '<script' "$data/report/static.html"; then echo "--static has a script"; exit 1; fi
test "$(grep -o '<svg' "$data/report/static.html" | wc -l)" -ge 4
grep -q "img-src data:\">" "$data/report/static.html"
rk-report "$t/out" --static --matplotlib -o "$data/report/static_mpl.html" --quiet
test "$(grep -o '<svg' "$data/report/static_mpl.html" | wc -l)" = "$(grep -o '<svg' "$data/report/static.html" | wc -l)"
rk-report "$t/out" --no-figures -o "$data/report/tables.html" --quiet
grep -q 'Figures left out' "$data/report/tables.html"
if grep -q '<svg' "$data/report/tables.html"; then echo "--no-figures drew figures"; exit 1; fi
echo ok
