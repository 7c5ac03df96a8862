#!/usr/bin/env bash
# CLI test rk_man_and_completion: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# The compiled tools (the build also copies the Python tools rk-plot, rk-report, rk-nightly, rk-slurm next to
# them: listed by rk help, documented in docs/, no man page or completion of their own yet).
is_elf() { [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '177ELF' ]; }
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
bin=$(dirname "$(command -v rk-sim)")
build=$(dirname "$bin")
comp=$build/completions
man=$build/man
tools=()
for t in "$bin"/rk-*; do
  [ -x "$t" ] && [ -f "$t" ] && is_elf "$t" || continue
  case "$(basename "$t")" in *.*) continue ;; esac
  tools+=("$(basename "$t")")
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
# rk: tool names, then the tool's own completion.
(PATH=$bin:$PATH; complete_words "$comp/rk" rk loc | grep -qx locate)
(PATH=$bin:$PATH; complete_words "$comp/rk" rk extract "" | grep -qx silhouette)
echo ok
