#!/usr/bin/env bash
# CLI test rk_report_deep_manifest: registered, and described, in tests/cli/rk_report.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
# The trial of rk_report_page (fixture report_pages), its manifest given an extra key 5000 levels deep, as
# trial.json may carry (SPEC.md §6: extra keys are kept) and rk-run copies into out/report.json.
t=$data/report/deep; rm -rf "$t"; cp -r "$data/report/page" "$t"; rm -f "$t/out/report.html"
python3 - "$t/out/report.json" <<'PY'
import json, sys
rep = json.load(open(sys.argv[1]))
rep["manifest"]["extra"] = "@"
text = json.dumps(rep, indent=1).replace('"@"', "[" * 2500 + "{\"k\": " * 2500 + "1" + "}" * 2500 + "]" * 2500)
open(sys.argv[1], "w").write(text)
PY
rk-report "$t/out" 2> "$data/report/deep.err"
cat "$data/report/deep.err"
python3 - "$t" "$data/report/page/out/report.html" <<'PY'
import re, sys
page, good = open(sys.argv[1] + "/out/report.html").read(), open(sys.argv[2]).read()
note = "nested deeper than 100 levels"
assert note + ": not shown" in page                               # the manifest, cut where it gets too deep
assert re.search(r"1 value\(s\) " + note + " are not shown", page)  # and a warning that says so
for part in ("tracked frames", "az/locate", "<svg"):                # the rest of the page as without the key
    assert page.count(part) == good.count(part), (part, page.count(part), good.count(part))
print("page ok:", len(page), "bytes")
PY
echo ok
