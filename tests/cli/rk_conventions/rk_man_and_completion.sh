#!/usr/bin/env bash
# CLI test rk_man_and_completion: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# Every tool of the build: the compiled ones and the Python tools rk-plot, rk-report, rk-nightly, rk-slurm
# that the build copies beside them (their argparse --help parsed by the same scripts/cli_manual.py).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
bin=$(dirname "$(command -v rk-sim)")
build=$(dirname "$bin")
comp=$build/completions
man=$build/man
tools=()
for t in "$bin"/rk-*; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  case "$(basename "$t")" in *.*) continue ;; esac
  tools+=("$(basename "$t")")
done
for t in rk-plot rk-report rk-nightly rk-slurm; do
  case " ${tools[*]} " in *" $t "*) ;; *) echo "FAIL: $t is not in $bin"; exit 1 ;; esac
done
for t in "${tools[@]}" rk; do
  [ -s "$comp/$t" ] || { echo "FAIL: no completion file $comp/$t"; exit 1; }
  bash -n "$comp/$t"
done
if command -v help2man >/dev/null; then
  for t in "${tools[@]}" rk; do
    [ -s "$man/$t.1" ] || { echo "FAIL: no man page $man/$t.1"; exit 1; }
    grep -q '^\.SH NAME' "$man/$t.1"
  done
  grep -q '^\.SS rk-extract beacon' "$man/rk-extract.1"
  grep -q 'Usage: rk-extract beacon' "$man/rk-extract.1"
  grep -q '^\.SS rk-slurm submit' "$man/rk-slurm.1"
  grep -A1 '^\.SH NAME' "$man/rk-report.1" | grep -q '^rk-report \\- the trial report page'
  grep -q 'max\\-points' "$man/rk-report.1"
  # Every page of docs/ a man page names exists (issue 27: the SEE ALSO of rk-nightly, rk-report, rk-slurm and
  # rk-attitude named docs/<tool>.md, which do not), and each tool's SEE ALSO names at least one.
  for t in "${tools[@]}"; do
    if ! sed -n '/^\.SH "SEE ALSO"/,/^\.SH/p' "$man/$t.1" | grep -q 'docs/'; then
      echo "FAIL: $t.1: SEE ALSO names no page"; exit 1
    fi
  done
  # No '§' in any --help (every subcommand's is in its tool's page): help2man wrote it as "??" ("SPEC.md ??6").
  if grep -l -e '§' -e '??' "$man"/*.1; then
    echo "FAIL: '§' or '??' in the man pages above (write 'section 6')"; exit 1
  fi
  named=$(cat "$man"/*.1 | grep -o 'docs/[A-Za-z0-9._\\-]*\.md' | tr -d '\\' | sort -u)
  [ -n "$named" ]
  for p in $named; do
    if [ ! -f "$src/$p" ]; then
      echo "FAIL: a man page names $p, which does not exist:"; grep -lF -e "$p" -e "${p//-/\\-}" "$man"/*.1; exit 1
    fi
  done
else
  echo "help2man not installed: man pages not checked"
fi
# Drive the completion functions the way bash does: COMP_WORDS/COMP_CWORD, then read COMPREPLY.
complete_words() {  # completion-file tool words... -> the candidates, one per line
  local file=$1; shift
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1));
           fn=$(complete -p "$1" | sed -E "s/.*-F ([^ ]+) .*/\1/"); "$fn"; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$file" "$@"
}
complete_words "$comp/rk-extract" rk-extract "" | grep -qx beacon
complete_words "$comp/rk-extract" rk-extract beacon --vi | grep -qx -- --video
complete_words "$comp/rk-extract" rk-extract beacon --rep | grep -qx -- --report   # common options after a subcommand
complete_words "$comp/rk-locate" rk-locate --tu | grep -qx -- --turret
complete_words "$comp/rk-locate" rk-locate --turret-interp "" | grep -qx cubic  # choice values
touch "$data/completion_probe.csv"
(cd "$data" && complete_words "$comp/rk-locate" rk-locate --track completion_probe | grep -qx completion_probe.csv)
# The Python tools: options, subcommands, file names after path options and for a positional argument,
# nothing after a number.
complete_words "$comp/rk-report" rk-report --max | grep -qx -- --max-points
(cd "$data" && complete_words "$comp/rk-report" rk-report completion_pro | grep -qx completion_probe.csv)
(cd "$data" && complete_words "$comp/rk-nightly" rk-nightly --log completion_pro | grep -qx completion_probe.csv)
[ -z "$(cd "$data" && complete_words "$comp/rk-nightly" rk-nightly --jobs completion_pro)" ]
complete_words "$comp/rk-slurm" rk-slurm "" | grep -qx submit
complete_words "$comp/rk-slurm" rk-slurm submit --max | grep -qx -- --max-parallel
complete_words "$comp/rk-plot" rk-plot --col | grep -qx -- --columns
# rk: tool names, then the tool's own completion.
(PATH=$bin:$PATH; complete_words "$comp/rk" rk loc | grep -qx locate)
(PATH=$bin:$PATH; complete_words "$comp/rk" rk extract "" | grep -qx silhouette)
echo ok
