#!/usr/bin/env bash
# CLI test rk_run_keeps_what_it_did_not_make: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/safety/keep; rm -rf "$d"; mkdir -p "$d"
t=$d/trial
fresh "$t"
# Item 7: out/ gets the umask's mode, not mkdtemp's 0700.
(umask 022; rk-run "$t" -q)
[ "$(stat -c %a "$t/out")" = 755 ] || { echo "FAIL: out/ mode $(stat -c %a "$t/out"), expected 755"; exit 1; }
test -f "$t/out/report.html"
plots=$(cd "$t/out" && ls plots | sort)
[ -n "$plots" ]
page_before=$(sha256sum < "$t/out/report.html")
# Item 4: --no-plots on an up-to-date trial keeps the plots and the page.
rk-run "$t" --no-plots > "$d/noplots1.out"
grep -q up-to-date "$d/noplots1.out"
[ "$(cd "$t/out" && ls plots | sort)" = "$plots" ] || { echo "FAIL: --no-plots removed plots"; exit 1; }
[ "$(sha256sum < "$t/out/report.html")" = "$page_before" ] || { echo "FAIL: --no-plots changed the page"; exit 1; }
# Item 5: the user's own files in out/ survive a rebuild (a changed input makes every step run).
printf 'my notes\n' > "$t/out/NOTES.txt"
mkdir -p "$t/out/analysis/deep"; printf '1,2\n' > "$t/out/analysis/deep/mine.csv"
ln -s ../trial.json "$t/out/manifest-link"
printf '# a comment\n' >> "$t/turret.csv"
rk-run "$t" --no-plots > "$d/noplots2.out"
grep -q 'kept 3 file(s) in out/ that rk-run did not make' "$t/rk-run.log" || { echo "FAIL: not said in rk-run.log"; exit 1; }
[ "$(cat "$t/out/NOTES.txt")" = "my notes" ] && [ "$(cat "$t/out/analysis/deep/mine.csv")" = "1,2" ] && [ -L "$t/out/manifest-link" ] \
  || { echo "FAIL: a rebuild lost the user's files"; exit 1; }
# ... and the stale plots are kept, marked stale; the page is remade without figures (current numbers).
[ "$(cd "$t/out" && ls plots | sort)" = "$plots" ] || { echo "FAIL: a --no-plots rebuild removed plots"; exit 1; }
python3 - "$t/out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
plots = [s for s in r["steps"] if s["kind"] == "plot"]
assert plots and all(s["status"] == "stale" for s in plots), [(s["id"], s["status"]) for s in plots]
PY
test -f "$t/out/report.html"
grep -q stale "$t/out/report.html" || { echo "FAIL: the page does not say the plots are stale"; exit 1; }
# The next run with plots redraws them (and still keeps the user's files).
rk-run "$t" > "$d/plots.out"
grep -Eq 'az/plot-[a-z]+ +ok' "$d/plots.out" || { cat "$d/plots.out"; echo "FAIL: stale plots not redrawn"; exit 1; }
test -f "$t/out/NOTES.txt"
# A user's file where a step now writes: refused, naming it; the old out/ as it was.
rm "$t/out/plots/"* "$t/out/steps/"*plot*; printf 'mine\n' > "$t/out/plots/$(echo "$plots" | head -n 1)"
python3 - "$t/out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
r["steps"] = [s for s in r["steps"] if s["kind"] != "plot"]   # the previous run made no plot
json.dump(r, open(sys.argv[1], "w"))
PY
before=$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)
"$expect" 4 - "out/plots/.*was not made by rk-run" -- rk-run "$t"
[ "$before" = "$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)" ] || { echo "FAIL: out/ changed"; exit 1; }
# A regular file named out: exit 4, never replaced.
fresh "$t"; printf 'not a folder\n' > "$t/out"
"$expect" 4 - "out: exists and is not a folder" -- rk-run "$t" --no-plots
[ "$(cat "$t/out")" = "not a folder" ]
# --out DIR (a trial on a read-only disk): products in DIR, rk-run's own files beside it, nothing created or
# changed in the trial folder; the second run is up to date.
fresh "$t"; touch "$d/marker"; sleep 0.01
rk-run "$t" --out "$d/products/t1" --no-plots -q
test -f "$d/products/t1/report.json" && test -f "$d/products/t1.last-run.json" && test -f "$d/products/t1.rk-run.log"
test -f "$d/products/.t1.rk-run.lock"
changed=$(find "$t" -newer "$d/marker")
[ -z "$changed" ] || { echo "FAIL: --out wrote into the trial folder: $changed"; exit 1; }
rk-run "$t" --out "$d/products/t1" --no-plots | grep -q up-to-date
echo ok
