#!/usr/bin/env bash
# CLI test extract_cli_decode_only: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract
rk-extract beacon --video "$x/beacon.mkv" --decode-only 2>&1 >/dev/null | grep -q 'decoded 60 frames'
