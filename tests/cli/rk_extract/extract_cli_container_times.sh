#!/usr/bin/env bash
# CLI test extract_cli_container_times: registered, and described, in tests/cli/rk_extract.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
x=$data/extract
rk-extract beacon --video "$x/beacon.mkv" -o "$x/track_own_times.csv" --report "$x/own_times.json"
rk-extract beacon --video "$x/beacon.mkv" --fps 20 -o "$x/track_fps.csv"
cmp "$x/track_own_times.csv" "$x/track_fps.csv"
grep -q '"source": "recording"' "$x/own_times.json"
grep -q '"container": 60' "$x/own_times.json"
