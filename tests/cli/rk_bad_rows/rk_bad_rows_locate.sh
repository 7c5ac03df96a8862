#!/usr/bin/env bash
# CLI test rk_bad_rows_locate: registered, and described, in tests/cli/rk_bad_rows.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/bad_rows.sh"
d=$data/locate; w=$data/bad_rows/locate; rm -rf "$w"; mkdir -p "$w"
nt=$(dirty "$d/track.csv" "$w/track.csv" x_px)
nu=$(dirty "$d/turret.csv" "$w/turret.csv" el_deg)
nr=$(dirty "$d/range.csv" "$w/range.csv" range_m)
cam=(--camera "$d/camera.json")
rk-locate --track "$d/track.csv" --turret "$d/turret.csv" --range "$d/range.csv" "${cam[@]}" -o "$w/clean.csv" -q
rk-locate --track "$w/track.csv" --turret "$w/turret.csv" --range "$w/range.csv" "${cam[@]}" -o "$w/skip.csv" \
  --bad-rows skip --report "$w/rep.json" 2> "$w/err"
cmp "$w/clean.csv" "$w/skip.csv"
report_ok "$w/rep.json" track "$nt" turret "$nu" range "$nr"
test "$(grep -c '^rk-locate: warning: .*:[0-9][0-9]*:[0-9][0-9]*: skipped bad row: ' "$w/err")" = $((nt + nu + nr))
grep -q "^rk-locate: warning: $w/turret.csv:[0-9]*:[0-9]*: skipped bad row: column 'el_deg': 'abc' is not a number" "$w/err"
grep -q "skipped bad row: column 't_s' goes backwards" "$w/err"
# --quiet: no warnings, same counts.
rk-locate --track "$w/track.csv" --turret "$w/turret.csv" "${cam[@]}" -o "$w/q.csv" --bad-rows skip -q 2> "$w/err_q"
test ! -s "$w/err_q"
# Strict by default and with --bad-rows error.
"$expect" 3 "$w/x.csv" 'track.csv:4:[0-9]+: row has 1 fields' -- rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv"
"$expect" 3 "$w/x.csv" 'turret.csv:[0-9]+:[0-9]+:' -- rk-locate --track "$d/track.csv" --turret "$w/turret.csv" "${cam[@]}" -o "$w/x.csv" --bad-rows error
"$expect" 2 "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --bad-rows maybe
# Failure reports: bad input (3), usage errors after and during parsing (2), unreadable input (4).
fails 3 "$w/r3.json" "$w/x.csv" "$w/track.csv" -- rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/r3.json"
fails 2 "$w/r2.json" "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --range-max-gap 0 --report "$w/r2.json"
fails 2 "$w/r2p.json" "$w/x.csv" -- rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report="$w/r2p.json" --bogus
fails 4 "$w/r4.json" "$w/x.csv" -- rk-locate --track "$w/no_such.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/r4.json"
# A failed run's report never replaces an input, nor the output it names.
cp "$d/turret.csv" "$w/turret_copy.csv"; cp "$w/clean.csv" "$w/clean_copy.csv"
rc=0; rk-locate --track "$w/track.csv" --turret "$w/turret_copy.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/turret_copy.csv" 2> /dev/null || rc=$?
test "$rc" = 3 && cmp "$d/turret.csv" "$w/turret_copy.csv"
rc=0; rk-locate --track "$d/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/clean_copy.csv" --report "$w/clean_copy.csv" 2> /dev/null || rc=$?
test "$rc" = 2 && cmp "$w/clean.csv" "$w/clean_copy.csv"
# A report that cannot be written does not change the exit code.
rc=0; rk-locate --track "$w/track.csv" --turret "$d/turret.csv" "${cam[@]}" -o "$w/x.csv" --report "$w/no_dir/r.json" 2> "$w/err_nr" || rc=$?
test "$rc" = 3 && grep -q '^rk-locate: warning: the report .* was not written' "$w/err_nr"
echo ok
