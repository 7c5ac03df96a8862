#!/usr/bin/env bash
# CLI test rk_run_skip_logic: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
t=$data/run/skip; fresh "$t"
rk-run "$t" --no-plots -q
ino=$(stat -c %i "$t/out"); rep=$(sha256sum < "$t/out/report.json")
rk-run "$t" --no-plots > "$data/run/skip1.out"; cat "$data/run/skip1.out"
grep -q 'up-to-date (0 run, 6 skipped' "$data/run/skip1.out"
test "$(stat -c %i "$t/out")" = "$ino"; test "$(sha256sum < "$t/out/report.json")" = "$rep"
touch "$t/turret.csv" "$t/az/video.mkv"
rk-run "$t" --no-plots > "$data/run/skip2.out"; grep -q 'up-to-date' "$data/run/skip2.out"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"locate": {"range-interp": "linear"}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots > "$data/run/skip3.out"; cat "$data/run/skip3.out"
grep -Eq '^az/extract-beacon +skipped +up to date' "$data/run/skip3.out"
grep -Eq '^az/locate +ok .*command line or options changed' "$data/run/skip3.out"
grep -Eq '^az/smooth +ok .*upstream changed: az/locate' "$data/run/skip3.out"
grep -Eq '^az/resample-range +skipped' "$data/run/skip3.out"
# The exports read the located target: it changed, so they run again (issue 34).
grep -Eq '^trajectory/export-kml +ok .*upstream changed: az/locate' "$data/run/skip3.out"
grep -q -- '--range-interp linear' "$t/out/steps/az.locate.log"
check_out --no-temporaries "$t"
echo "# edited: the content changes, the data do not" >> "$t/range.csv"
rk-run "$t" --no-plots > "$data/run/skip4.out"; cat "$data/run/skip4.out"
grep -Eq '^az/locate +ok .*input changed: range.csv' "$data/run/skip4.out"
grep -Eq '^az/resample-range +ok .*input changed: range.csv' "$data/run/skip4.out"
grep -Eq '^az/extract-beacon +skipped' "$data/run/skip4.out"
rk-run "$t" --no-plots --force > "$data/run/skip5.out"; grep -q 'done (6 run, 0 skipped' "$data/run/skip5.out"
# Switching a step off rebuilds out/ without its product.
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"]["resample-range"] = False
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots -q; test ! -e "$t/out/az/range_at_frames.csv"; test -s "$t/out/az/located.csv"
rk-run "$t" --no-plots --dry-run | grep -Eq '^az/resample-range +off'
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); del j["steps"]["resample-range"]
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots | grep -Eq '^az/resample-range +ok .*new step \(was off\)'
check_out --no-temporaries "$t"
echo ok
