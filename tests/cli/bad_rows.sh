# Shell helpers for the --bad-rows and failure-report CLI tests (rk_bad_rows.cmake); sourced.

# dirty IN OUT [COLUMN]: IN with bad rows after its second data row: a garbage line, t_s "nan",
# t_s going backwards, one field too many and, with COLUMN, "abc" and "inf" in COLUMN.
# Prints the number of bad rows added.
dirty() {
  awk -F, -v col="${3:-}" '
    function emit(a, n,   i, s) { s = a[1]; for (i = 2; i <= n; i++) s = s "," a[i]; print s }
    /^[ \t]*#/ || NF == 0 { print; next }
    !h { h = 1; for (i = 1; i <= NF; i++) { if ($i == "t_s") ct = i; if ($i == col) cv = i }; print; next }
    { print; n++ }
    n == 2 && !done { done = 1; m = NF
      print "@@ serial garbage @@"
      split($0, a, ","); a[ct] = "nan"; emit(a, m)
      split($0, a, ","); a[ct] = sprintf("%.6f", a[ct] - 1000); emit(a, m)
      print $0 ",9"
      added = 4
      if (cv) { split($0, a, ","); a[cv] = "abc"; emit(a, m); split($0, a, ","); a[cv] = "inf"; emit(a, m); added += 2 }
    }
    END { if (!done) exit 1; print added > "/dev/stderr" }' "$1" > "$2" 2> "$2.added"
  cat "$2.added"; rm -f "$2.added"
}

# skip_same W ROLE N [ROLE N ...] -- CMD ARG...: an argument @F stands for W/clean/F in one run and for
# W/F (its dirty copy) in the other, with --bad-rows skip; both runs write -o, and the outputs must be
# byte-identical, with each ROLE's rows_skipped N in the report W/skip.json.
skip_same() {
  local w=$1 roles=() clean=() skip=() a
  shift
  while [ "$1" != "--" ]; do roles+=("$1"); shift; done
  shift
  for a in "$@"; do
    case "$a" in
      @*) clean+=("$w/clean/${a#@}"); skip+=("$w/${a#@}") ;;
      *) clean+=("$a"); skip+=("$a") ;;
    esac
  done
  "${clean[@]}" -o "$w/clean.out" -q
  "${skip[@]}" -o "$w/skip.out" -q --bad-rows skip --report "$w/skip.json"
  cmp "$w/clean.out" "$w/skip.out"
  report_ok "$w/skip.json" "${roles[@]}"
}

# dirty_in W FILE [COLUMN]: copies FILE to W/clean/ and its dirty version to W/ (same name); prints
# the number of bad rows added.
dirty_in() {
  mkdir -p "$1/clean"
  cp "$2" "$1/clean/"
  dirty "$2" "$1/$(basename "$2")" "${3:-}"
}

# report_ok REPORT ROLE N: REPORT says status ok, exit code 0 and ROLE's rows_skipped is N.
report_ok() {
  python3 - "$@" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["status"] == "ok" and r["exit_code"] == 0, (r.get("status"), r.get("exit_code"))
for role, n in zip(sys.argv[2::2], sys.argv[3::2]):
    got = r["inputs"][role].get("rows_skipped")
    assert got == int(n), "%s: rows_skipped %s, expected %s" % (role, got, n)
PY
}

# fails CODE REPORT OUTPUT [INPUT] -- command...: the command exits CODE, leaves no OUTPUT, and
# REPORT is a failure report (status failed, exit_code CODE, error = the stderr error line) that
# lists INPUT among the inputs read (when given).
fails() {
  local code=$1 rep=$2 out=$3 input=""
  shift 3
  if [ "$1" != "--" ]; then input=$1; shift; fi
  shift
  rm -f "$rep" "$out"
  local rc=0
  "$@" > "$rep.stdout" 2> "$rep.stderr" || rc=$?
  if [ "$rc" != "$code" ]; then echo "FAIL: exit $rc, expected $code: $*"; cat "$rep.stderr"; return 1; fi
  if [ -e "$out" ]; then echo "FAIL: partial output $out: $*"; return 1; fi
  if [ ! -s "$rep" ]; then echo "FAIL: no report $rep: $*"; cat "$rep.stderr"; return 1; fi
  python3 - "$rep" "$code" "$rep.stderr" "$input" <<'PY' || { echo "FAIL: $*"; cat "$rep"; return 1; }
import json, sys
rep, code, errfile, inp = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
r = json.load(open(rep))
assert r["status"] == "failed", r["status"]
assert r["exit_code"] == code, r["exit_code"]
for k in ("tool", "version", "command_line", "inputs"):
    assert k in r, k
lines = open(errfile).read().splitlines()
assert r["tool"] + ": error: " + r["error"] in lines, (r["error"], lines)
if inp:
    assert any(v.get("path") == inp for v in r["inputs"].values() if isinstance(v, dict)), r["inputs"]
PY
  rm -f "$rep.stdout" "$rep.stderr"
}
