#!/usr/bin/env bash
# Runs a command that must fail the SPEC.md §4 way, and checks it did:
#   expect.sh CODE OUTPUT [PATTERN] -- command args...
# CODE     expected exit code
# OUTPUT   a path that must NOT exist afterwards (no partial output), or "-" for none
# PATTERN  optional extended regex the error line must match (e.g. 'track.csv:7:')
# Checks: exit code == CODE; stderr's first line starts "rk-<tool>: error: "; stderr
# is one line; stdout is empty; OUTPUT absent.
set -u
code=$1; out=$2; shift 2
pattern=""
if [ "$1" != "--" ]; then pattern=$1; shift; fi
[ "$1" = "--" ] && shift
errfile=$(mktemp); outfile=$(mktemp)
"$@" >"$outfile" 2>"$errfile"
rc=$?
fail=0
if [ "$rc" != "$code" ]; then echo "FAIL: exit code $rc, expected $code"; fail=1; fi
first=$(head -n 1 "$errfile")
if ! [[ "$first" =~ ^rk-[a-z]+:\ error:\  ]]; then echo "FAIL: stderr does not start with 'rk-<tool>: error: '"; fail=1; fi
lines=$(grep -c '' "$errfile")
if [ "$lines" != "1" ]; then echo "FAIL: stderr has $lines lines, expected 1"; fail=1; fi
if [ -s "$outfile" ]; then echo "FAIL: stdout is not empty"; fail=1; fi
if [ -n "$pattern" ] && ! grep -Eq -- "$pattern" "$errfile"; then echo "FAIL: error does not match /$pattern/"; fail=1; fi
if [ "$out" != "-" ] && [ -e "$out" ]; then echo "FAIL: output $out exists (partial output)"; fail=1; fi
echo "--- command: $*"; echo "--- stderr:"; cat "$errfile"
rm -f "$errfile" "$outfile"
exit $fail
