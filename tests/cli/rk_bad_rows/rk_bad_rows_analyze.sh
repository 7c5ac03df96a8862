#!/usr/bin/env bash
# CLI test rk_bad_rows_analyze: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/analyze; w=$data/bad_rows/analyze; rm -rf "$w"; mkdir -p "$w"
ne=$(dirty "$d/est.csv" "$w/est.csv" range_m)
nr=$(dirty "$d/ref.csv" "$w/ref.csv" az_deg)
c=(--columns az_deg,range_m)
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/clean.json" --errors "$w/clean.csv" -q
rk-analyze compare --estimate "$w/est.csv" --reference "$w/ref.csv" "${c[@]}" -o "$w/skip.json" --errors "$w/skip.csv" \
  --bad-rows skip --report "$w/rep.json" -q
cmp "$w/clean.csv" "$w/skip.csv"
python3 -c 'import json,sys; a, b = (json.load(open(f)) for f in sys.argv[1:]); assert a["columns"] == b["columns"] and a["rows"] == b["rows"]' \
  "$w/clean.json" "$w/skip.json"
report_ok "$w/rep.json" estimate "$ne" reference "$nr"
"$expect" 3 "$w/x.json" 'est.csv:[0-9]+:[0-9]+:' -- rk-analyze compare --estimate "$w/est.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/x.json"
fails 3 "$w/r3.json" "$w/x.json" "$d/est_text.csv" -- rk-analyze compare --estimate "$d/est_text.csv" --reference "$d/ref.csv" --columns range_m -o "$w/x.json" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.json" -- rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" "${c[@]}" --interp quintic -o "$w/x.json" --report "$w/r2.json"
fails 4 "$w/r4.json" "$w/x.json" -- rk-analyze compare --estimate "$w/no_such.csv" --reference "$d/ref.csv" "${c[@]}" -o "$w/x.json" --report "$w/r4.json"
echo ok
