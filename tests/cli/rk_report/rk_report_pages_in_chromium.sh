#!/usr/bin/env bash
# CLI test rk_report_pages_in_chromium: registered, and described, in tests/cli/rk_report.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
check=$src/tests/cli/browser_check.py
if ! command -v chromium > /dev/null && [ -z "${RK_CHROMIUM:-}" ]; then
  echo "SKIPPED: chromium is not installed (scripts/setup.sh --browser installs it; CI does)"; exit 77
fi
t=$data/report/page                   # made by rk_report_page
pct=$(json "$t/out/report.json" '"%.1f %%" % (100 * [s for s in d["steps"] if s["id"] == "az/extract-beacon"][0]["quality"]["ok_fraction"])')
python3 "$check" "$t/out/report.html" --expect "$pct" --expect "az/extract-beacon" --expect "Warnings"
# The interactive figures (issue 34), driven by playwright-core: a zoom box dragged to a 1-s window on the azimuth
# panel and back, every panel of the unit following, the read-out at the cursor equal to located.csv's row.
# (Its first paint under playwright includes SwiftShader's WebGL start, 0.5-1.1 s here: held to 3 s, not the
# 1.5 s target, which rk_report_hour_page times over the DevTools pipe.)
if command -v node > /dev/null; then
  node "$src/tests/cli/report_interactive.mjs" "$t/out/report.html" --csv "$t/out/az/located.csv" --group az \
    --column az_deg --window 1 --max-fcp-ms 3000
else
  echo "node is not installed: the interactive figures were not driven (scripts/setup.sh installs it)"
fi
# A nightly root: the good trial and one that fails (a bad range row); the index lists the failure first.
r=$data/report/nightly; rm -rf "$r"; mkdir -p "$r"
cp -r "$t" "$r/good"; fresh "$r/bad"
awk -F, 'NR == 4 { $2 = "x" } { print }' OFS=, "$r/bad/range.csv" > "$r/tmp" && mv "$r/tmp" "$r/bad/range.csv"
set +e; rk-nightly "$r" -j 1 -q > /dev/null; rc=$?; set -e
test "$rc" = 1
test -s "$r/index.html"
python3 "$check" "$r/index.html" --expect "$pct" --expect "range.csv:4:" --expect "failed"
python3 - "$r/index.html" <<'PY'
import sys
page = open(sys.argv[1]).read()
assert page.index(">bad<") < page.index(">good<"), "failures first"
assert 'href="good/out/report.html"' in page
PY
echo ok
