#!/usr/bin/env bash
# CLI test rk_python_tools_refuse_abbreviations: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
s=$src/scripts
d=$data/abbrev; rm -rf "$d"; mkdir -p "$d/out" "$d/root"
printf 't_s,az_deg\n0,1\n1,2\n' > "$d/a.csv"
echo '{"tool": "rk-run"}' > "$d/out/report.json"   # the least rk-report makes a page of
L() { "$expect" "$@"; }
# Each is a prefix of a real option (--output, --summary, --max-parallel, --check): a usage error (exit 2), and
# the path it would have reached is not written.
# rk-plot as rk-run called it for "steps": {"az/plot": {"out": ...}}: its own -o, then the manifest's --out.
L 2 "$d/victim.png" 'unrecognized arguments: --out' -- "$s/rk-plot" -i "$d/a.csv" --columns az_deg -o "$d/plot.png" \
  --out "$d/victim.png"
test ! -e "$d/plot.png"
L 2 "$d/victim.html" 'unrecognized arguments: --out' -- "$s/rk-report" "$d/out" --out "$d/victim.html"
L 2 "$d/victim.json" 'unrecognized arguments: --summ' -- "$s/rk-nightly" "$d/root" --rk-run /bin/true \
  --summ "$d/victim.json"
test ! -e "$d/root/index.html" && test ! -e "$d/root/.rk-nightly"
L 2 - 'unrecognized arguments: --max-par' -- "$s/rk-slurm" submit "$d/root" --max-par 2
# The repository's own scripts too (plain argparse: usage line, then the error).
set +e
python3 "$s/long_functions.py" --chec "$d/a.csv" > "$d/lf.out" 2>&1; rc1=$?
python3 "$s/golden_outputs.py" "$d/no-bin" "$d/golden" --chec "$d/no-digests.txt" > "$d/go.out" 2>&1; rc2=$?
set -e
test "$rc1" = 2 && grep -q 'unrecognized arguments: --chec' "$d/lf.out"
test "$rc2" = 2 && grep -q 'unrecognized arguments: --chec' "$d/go.out" && test ! -e "$d/golden"
# The full name still works (rk-plot's: rk_plot_png).
"$s/rk-report" "$d/out" --output "$d/ok.html" --quiet && test -s "$d/ok.html"
echo ok
