#!/usr/bin/env bash
# CLI test rk_dispatcher: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# Every tool of the build: the compiled ones and the Python tools rk-plot, rk-report, rk-nightly, rk-slurm
# that the build copies beside them (with rk_version.py: the same version and commit).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
bin=$(dirname "$(command -v rk-sim)")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Every rk-* executable of the build is listed, one line each with a description.
rk help > "$out/help.txt"
n_tools=0
for t in "$bin"/rk-*; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  name=$(basename "$t"); name=${name#rk-}
  case "$name" in *.*) continue ;; esac
  n_tools=$((n_tools + 1))
  grep -Eq "^  $name +[A-Za-z]" "$out/help.txt" || { echo "FAIL: rk help does not list $name"; cat "$out/help.txt"; exit 1; }
done
[ "$n_tools" -ge 10 ] || { echo "FAIL: only $n_tools tools found in $bin"; exit 1; }
# rk <tool> is rk-<tool>: same stdout, same exit code.
rk locate --help > "$out/a.txt"; rk-locate --help > "$out/b.txt"; cmp "$out/a.txt" "$out/b.txt"
rk help locate > "$out/c.txt"; cmp "$out/a.txt" "$out/c.txt"
set +e
rk locate --track "$out/missing.csv" --camera x --turret y -o "$out/o.csv" 2> "$out/err.txt"; rc=$?
set -e
[ "$rc" = 4 ] || { echo "FAIL: rk locate on a missing file exited $rc, rk-locate exits 4"; cat "$out/err.txt"; exit 1; }
grep -q '^rk-locate: error: ' "$out/err.txt"
[ ! -e "$out/o.csv" ]
# Unknown tool: usage error.
set +e
rk no-such-tool 2> "$out/err.txt"; rc=$?
set -e
[ "$rc" = 2 ] && grep -q "^rk: error: unknown tool 'no-such-tool'" "$out/err.txt"
# --version of rk and of every tool: version and a git commit (12 hex digits, or 'unknown' outside git).
rk --version | grep -Eq '^rk \(rangekit\) [0-9]+\.[0-9]+\.[0-9]+ \(git ([0-9a-f]{12}|unknown)\)$'
commit=$(rk --version | sed -E 's/.*\(git (.*)\)$/\1/')
if git -C "$src" rev-parse HEAD >/dev/null 2>&1; then
  head=$(git -C "$src" rev-parse --short=12 HEAD)
  [ "$commit" = "$head" ] || { echo "FAIL: rk --version names $commit, the checkout is at $head"; exit 1; }
fi
n_py=0
for t in "$bin"/rk-*; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  case "$(basename "$t")" in *.*) continue ;; esac
  "$t" --version | grep -Eqx "$(basename "$t") \(rangekit\) [0-9]+\.[0-9]+\.[0-9]+ \(git $commit\)" ||
    { echo "FAIL: $t --version is not 'NAME (rangekit) VERSION (git $commit)'"; "$t" --version; exit 1; }
  head -c 2 "$t" | grep -q '#!' && n_py=$((n_py + 1))
done
[ "$n_py" -ge 4 ] || { echo "FAIL: only $n_py Python tools checked"; exit 1; }
# The Python tools' version is the compiled tools' (one owner: CMakeLists.txt's project()).
[ "$(rk-report --version | sed -E 's/.*\) ([0-9.]+) \(.*/\1/')" = "$(rk --version | sed -E 's/.*\) ([0-9.]+) \(.*/\1/')" ]
echo ok
