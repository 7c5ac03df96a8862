#!/usr/bin/env bash
# CLI test rk_nightly_page_failures: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/pages; r=$d/root; rm -rf "$d"; mkdir -p "$d/bin"
# A stand-in rk-run (lib.sh): "done", and for the trial "nopage" rk-run's warning that its report page could not
# be made; the trials' out/report.json are written below, as a last good run left them.
standin_rk_run "$d/bin/rk-run"
python3 - "$r" <<'PY'
import json, os, sys
root = sys.argv[1]
step = {"id": "az/extract-beacon", "unit": "az", "kind": "extract-beacon",
        "quality": {"rows": 40, "ok_fraction": 0.925, "status": {"ok": 37, "lost": 3}}}
for t in ("ok", "deep", "nopage", "damaged"):
    os.makedirs(os.path.join(root, t, "out"))
    manifest = {"name": t}
    if t == "deep":  # an extra key, 5000 levels deep: legal (SPEC.md §6), and rk-run copies it into report.json
        manifest["extra"] = "[" * 5000 + "]" * 5000
    rep = {"tool": "rk-run", "result": "done", "steps": [dict(step)], "manifest": manifest}
    if t == "damaged":  # a report.json the index cannot read a headline figure from
        rep["steps"][0]["quality"] = dict(step["quality"], status="x")
    for name, doc in (("trial.json", manifest), ("out/report.json", rep)):
        text = json.dumps(doc)
        if t == "deep":
            text = text.replace('"' + manifest["extra"] + '"', manifest["extra"])
        open(os.path.join(root, t, name), "w").write(text)
    open(os.path.join(root, t, "out", "report.html"), "w").write("<html></html>\n")
PY
set +e; rk-nightly "$r" --rk-run "$d/bin/rk-run" -q > "$d/nightly.out" 2>&1; rc=$?; set -e
cat "$d/nightly.out"
# A page not made is a failed night (exit 1, the table printed even with -q), yet every trial is listed.
test "$rc" = 1
test -s "$r/index.html" || { echo "no index.html"; exit 1; }
python3 - "$r" <<'PY'
import json, sys
root = sys.argv[1]
page = open(root + "/index.html").read()
for t in ("ok", "deep", "nopage", "damaged"):
    assert ">%s<" % t in page, t
assert page.count("92.5 %") == 3, page.count("92.5 %")          # ok, deep and nopage: figures read
assert "row not made" in page and "AttributeError" in page       # damaged: its row says why
s = json.load(open(root + "/rk-nightly-summary.json"))
got = sorted((p["trial"], p["reason"].split(":")[0]) for p in s["pages_not_made"])
assert got == [("damaged", "row of index.html not made"), ("nopage", "stand-in")], got
assert s["counts"]["done"] == 4, s["counts"]
reason = [t["reason"] for t in s["trials"] if t["trial"] == "nopage"][0]
assert reason == "report page not made: stand-in", reason
PY
grep -q '^page not made: nopage: stand-in' "$r/rk-nightly-summary.txt"
grep -q '^page not made: damaged: row of index.html not made' "$d/nightly.out"
echo ok
