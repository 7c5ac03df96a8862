#!/usr/bin/env bash
# CLI test import_cli_asterix_real: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
real=${RK_REAL_DATA:-$src/../shared/data/real}
if [ ! -f "$real/cat_034_048.pcap" ]; then
  echo "SKIP: the real radar feed is not in $real"
  exit 77
fi
if ! command -v tshark > /dev/null; then
  echo "SKIP: tshark (Debian's tshark, the independent decoder) is not installed"
  exit 77
fi
d=$data/import/asterix_real
mkdir -p "$d"
rk-import asterix --input "$real/cat_034_048.pcap" --epoch-utc 2016-05-05T00:00:00Z -o "$d/plots.csv" \
  --report "$d/plots.json" 2> "$d/err"
cat "$d/err"
# Every CAT048 target report Wireshark's dissector decodes is in the plots once (the feed sends each twice).
/usr/bin/python3 "$src/tests/cli/rk_import/asterix_vs_tshark.py" "$real/cat_034_048.pcap" "$d/plots.csv" 2016-05-05T00:00:00Z
/usr/bin/python3 - "$d/plots.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))["asterix"]
assert a["bad_records"] == 0 and a["inputs"][0]["packets"] == 100, a
# Each datagram on two groups from two senders: the copies are counted against the second source of each pair.
assert a["duplicates"] > 0 and sum(s["duplicates"] for s in a["sources"]) == a["duplicates"], a["sources"]
assert 0 < a["capture_minus_record_s"] < 5, a["capture_minus_record_s"]
PY
echo PASS
