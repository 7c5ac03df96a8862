#!/usr/bin/env bash
# CLI test rk_nightly_summary: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
r=$data/run/nightly; rm -rf "$r"; mkdir -p "$r/site"
fresh "$r/t1"; fresh "$r/site/t2"; fresh "$r/site/t3"
awk -F, 'NR == 4 { $2 = "x" } { print }' OFS=, "$r/site/t3/range.csv" > "$r/tmp" && mv "$r/tmp" "$r/site/t3/range.csv"
set +e; rk-nightly "$r" -j 2 --no-plots > "$data/run/nightly1.out" 2>&1; rc=$?; set -e
cat "$data/run/nightly1.out"
test "$rc" = 1
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 2, 'up_to_date': 0, 'skipped_locked': 0, 'failed': 1}"
json "$r/rk-nightly-summary.json" '[t for t in d["trials"] if t["trial"]=="site/t3"][0]["reason"]' | grep -q 'range.csv:4:'
grep -Eq '^site/t3 +failed' "$r/rk-nightly-summary.txt"
grep -q 'summary:' "$r/rk-nightly.log"
check_out --no-temporaries "$r/t1" "$r/site/t2"
check_out --allow-missing --no-temporaries "$r/site/t3"
cp "$data/small/range.csv" "$r/site/t3/range.csv"
rk-nightly "$r" --no-plots -q     # quiet and successful: prints nothing
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 1, 'up_to_date': 2, 'skipped_locked': 0, 'failed': 0}"
# The trend (issue 34): each night's summary is kept (.rk-nightly/history/), with every trial's numeric headline
# figures; the index draws them against the night. An older night is put in by hand with t1's tracked-frame
# fraction 0.2 lower: the index shows t1's figure over three nights and its change.
json "$r/rk-nightly-summary.json" '[t for t in d["trials"] if t["trial"]=="t1"][0]["headline"][0]["label"]' | grep -q 'tracked frames'
test "$(ls "$r/.rk-nightly/history" | wc -l)" = 2
python3 - "$r" <<'PY'
import glob, json, sys
r = sys.argv[1]
first = sorted(glob.glob(r + "/.rk-nightly/history/summary-*.json"))[0]
s = json.load(open(first))
s["started_utc"] = "2026-10-01T02:00:00Z"
for t in s["trials"]:
    for f in t.get("headline", []):
        if t["trial"] == "t1" and "tracked frames" in f["label"]:
            f["value"] -= 0.2
json.dump(s, open(r + "/.rk-nightly/history/summary-20261001T020000Z.json", "w"))
PY
rk-nightly "$r" --no-plots -q
python3 - "$r" <<'PY'
import json, re, sys
r = sys.argv[1]
page = open(r + "/index.html").read()
trend = page[page.index('id="trend"'):]
assert "Trend of the headline figures" in page
assert "<h3>t1</h3>" in trend and "<svg" in trend, trend[:500]
row = re.search(r"<td>az tracked frames</td><td class=\"num\">(\d+)</td><td class=\"num\">([^<]*)</td><td class=\"num\">([^<]*)</td><td class=\"num\">([^<]*)</td>", trend)
assert row and row.group(1) == "4", row and row.groups()     # the hand-made night, the two runs and this one
assert row.group(4).startswith("+"), row.groups()            # 0.2 up since the first night
print("trend:", row.groups())
PY
# The history is rk-nightly's own folder: made a link to a folder elsewhere, it is neither followed nor written
# through (a warning in the log), and nothing there is read, written or removed.
mv "$r/.rk-nightly/history" "$data/run/history.real"; rm -rf "$data/run/elsewhere"; mkdir -p "$data/run/elsewhere"
echo '{"started_utc": "2026-01-01T00:00:00Z", "trials": []}' > "$data/run/elsewhere/summary-0.json"
ln -s "$data/run/elsewhere" "$r/.rk-nightly/history"
rk-nightly "$r" --no-plots -q
test "$(ls -A "$data/run/elsewhere")" = summary-0.json
grep -q 'not kept for the trend' "$r/rk-nightly.log"
grep -q 'A trend needs two nights or more' "$r/index.html"
rm "$r/.rk-nightly/history"; mv "$data/run/history.real" "$r/.rk-nightly/history"
# The holder's output goes to a file: a sleep left on the test's stdout kept ctest waiting for its 60 s.
flock -o "$r/.rk-nightly/lock" sleep 60 > "$data/run/nightly_holder.out" 2>&1 & holder=$!
while flock -n "$r/.rk-nightly/lock" true; do sleep 0.05; done
set +e; timeout 30 rk-nightly "$r" --no-plots 2> "$data/run/nightly2.err"; rc=$?; set -e
kill $(pgrep -P "$holder") "$holder"; wait "$holder" 2>/dev/null || true
test "$rc" = 75; grep -q 'another rk-nightly' "$data/run/nightly2.err"   # at once, not after the holder
echo ok
