#!/usr/bin/env bash
# CLI tests devnull_before / devnull_after (tests/cli/rk_outputs.cmake): the suite never damages the machine.
# /dev/null must be a character device, and none of /dev/null, /dev/stdout, /dev/stderr, /dev/stdin may have
# become a regular file (a tool that renamed its output over one of them; /dev/stdout was once found so on a
# development machine). stat without -L: the entry itself, not what a link points at.
set -u
test -c /dev/null || { echo "/dev/null is not a character device" >&2; exit 1; }
for f in /dev/null /dev/stdout /dev/stderr /dev/stdin; do
  [ -e "$f" ] || [ -L "$f" ] || continue
  case "$(stat -c %F "$f")" in
    "regular file"|"regular empty file") echo "$f is a regular file: something replaced it" >&2; exit 1 ;;
  esac
done
