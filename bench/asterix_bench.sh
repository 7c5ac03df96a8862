#!/usr/bin/env bash
# Decoding a radar feed (issue 30): `rk-import asterix` on a pcap in the page cache, one core, against the target of
# one million target reports per second. The feed: REPORTS CAT048 target reports (the items of a Mode S radar's
# report: 010, 140, 020, 040, 070, 090, 130, 220, 240, 250, 161, 200, 170, 230: 52 octets) in datagrams of 10
# reports, every datagram sent twice (a redundant feed on two groups, as real feeds are), a CAT034 north marker
# every 4 s. Three timings, median of REPEATS runs each, files warmed into the page cache first:
#   decode   rk-import asterix with -o /dev/null-like output to a file under OUT (the whole tool: decode,
#            duplicates, sort, CSV);
#   cat      cat FILE > /dev/null: the floor (reading the file);
#   reports/s = distinct reports / decode time.
#   bench/asterix_bench.sh [OUT]      needs a Release build in build/ (scripts/setup.sh)
# Environment: REPORTS (default 2000000), REPEATS (default 5).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=${RK_BIN:-$ROOT/build/apps}
OUT=${1:-/tmp/rk-asterix-bench}
REPORTS=${REPORTS:-2000000}
REPEATS=${REPEATS:-5}
mkdir -p "$OUT"
/usr/bin/python3 - "$OUT/feed.pcap" "$REPORTS" <<'PY'
import struct, sys
path, n = sys.argv[1], int(sys.argv[2])
DAY0 = 1462406400.0
def record(items):
    last = max(items); f = bytearray((last + 6) // 7)
    for frn in items: f[(frn - 1) // 7] |= 1 << (7 - (frn - 1) % 7)
    for i in range(len(f) - 1): f[i] |= 1
    return bytes(f) + b"".join(items[x] for x in sorted(items))
def frame(src, group, payload):
    udp = struct.pack(">HHHH", 20000 + src, 21000, len(payload) + 8, 0) + payload
    ip = struct.pack(">BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), 1, 0, 64, 17, 0, bytes([10, 0, 0, src]), bytes([232, group, 1, 1])) + udp
    return b"\x01" * 6 + b"\x02" * 6 + b"\x08\x00" + ip
with open(path, "wb") as f:
    f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
    per = 10
    t0 = 36000.0
    fixed = {3: b"\xa0", 5: b"\x02\x00", 7: b"\xa0\x40\x50", 8: b"\x3c\x66\x0c", 9: b"DLH65A", 10: b"\x01" + bytes(8),
             13: b"\x00\x10\x58\x00", 14: b"\x40", 21: b"\x20\x7d"}
    for k in range(0, n, per):
        t = t0 + k / 2000.0  # 2000 reports a second
        recs = []
        for j in range(per):
            i = k + j
            items = dict(fixed)
            items[1] = bytes([25, 10 + i % 4])
            items[2] = struct.pack(">I", int(t * 128))[1:]
            items[4] = struct.pack(">HH", 1000 + i % 50000, (i * 37) % 65536)
            items[6] = struct.pack(">H", (100 + i % 300) * 4)
            items[11] = struct.pack(">H", i % 4096)
            recs.append(record(items))
        body = b"".join(recs)
        block = struct.pack(">BH", 48, len(body) + 3) + body
        for src, group, dt in ((1, 1, 0.0), (2, 2, 0.0001)):
            fr = frame(src, group, block)
            ts = DAY0 + t + 0.3 + dt
            sec = int(ts)
            f.write(struct.pack("<IIII", sec, int((ts - sec) * 1e6), len(fr), len(fr)) + fr)
PY
cat "$OUT/feed.pcap" > /dev/null
size=$(stat -c %s "$OUT/feed.pcap")
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
t_dec=$(for _ in $(seq "$REPEATS"); do
  /usr/bin/time -f %e taskset -c 0 "$B/rk-import" asterix --input "$OUT/feed.pcap" --epoch-utc 2016-05-05T00:00:00Z \
    -o "$OUT/plots.csv" --quiet 2>&1 >/dev/null | tail -1
done | median)
t_cat=$(for _ in $(seq "$REPEATS"); do /usr/bin/time -f %e cat "$OUT/feed.pcap" 2>&1 >/dev/null | tail -1; done | median)
rows=$(grep -vc '^#' "$OUT/plots.csv")
rows=$((rows - 1))
echo "| feed | reports (distinct) | pcap MB | rk-import asterix (s) | cat (s) | distinct reports/s | records walked/s (copies too) |"
echo "|---|---|---|---|---|---|---|"
awk -v r="$rows" -v s="$size" -v d="$t_dec" -v c="$t_cat" 'BEGIN {
  printf "| CAT048, 10 reports a datagram, each datagram twice | %d | %.0f | %.2f | %.2f | %.2f M | %.2f M |\n", r, s / 1e6, d, c, r / d / 1e6, 2 * r / d / 1e6 }'
