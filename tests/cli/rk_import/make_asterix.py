#!/usr/bin/python3
"""Synthetic ASTERIX feeds for rk-import asterix's CLI tests, written here without rangekit's code.

    make_asterix.py DIR

DIR/feed.pcap: two radars (SAC 25 SIC 10 with a position in DIR/radars.json, SAC 25 SIC 11 without), 12 s of
CAT048 target reports (one aircraft, with Mode C, and from SIC 10 a 3-D height) and CAT034 north markers every
4 s, every datagram sent twice (two senders, two groups), starting at 2016-05-05T23:59:55Z (over midnight).
DIR/bad.pcap: the same first second with one block whose length runs past its datagram, and one record with a
spare FRN. DIR/feed.ast: the target reports of feed.pcap as a raw record stream. DIR/truth.csv: what the plots
must hold (t_s from 2016-05-05T23:59:50Z).
"""
import json
import os
import struct
import sys

DAY0 = 1462406400.0  # 2016-05-05T00:00:00Z
T0 = DAY0 + 86395.0  # first report
EPOCH = DAY0 + 86390.0


def record(items):
    """items: {frn: bytes} -> FSPEC + items in FRN order."""
    last = max(items)
    fspec = bytearray((last + 6) // 7)
    for frn in items:
        fspec[(frn - 1) // 7] |= 1 << (7 - (frn - 1) % 7)
    for i in range(len(fspec) - 1):
        fspec[i] |= 1
    return bytes(fspec) + b"".join(items[f] for f in sorted(items))


def block(cat, records):
    body = b"".join(records)
    return struct.pack(">BH", cat, len(body) + 3) + body


def tod(t):
    return struct.pack(">I", round(((t - DAY0) % 86400) * 128))[1:]


def cat048(sic, t, rho_nm, theta_deg, fl, height_ft=None):
    items = {1: bytes([25, sic]), 2: tod(t), 3: bytes([0xA0]),
             4: struct.pack(">HH", round(rho_nm * 256), round(theta_deg / 360 * 65536) % 65536),
             5: struct.pack(">H", 0o4321), 6: struct.pack(">H", round(fl * 4) & 0x3FFF),
             8: bytes([0x12, 0x34, 0x56]), 11: struct.pack(">H", 42)}
    if height_ft is not None:
        items[19] = struct.pack(">H", round(height_ft / 25) & 0x3FFF)
    return record(items)


def cat034_north(sic, t):
    return record({1: bytes([25, sic]), 2: bytes([1]), 3: tod(t), 5: struct.pack(">H", 4 * 128)})


def udp_frame(src, dst, sport, dport, payload):
    udp = struct.pack(">HHHH", sport, dport, len(payload) + 8, 0) + payload
    ip = struct.pack(">BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), 1, 0, 64, 17, 0, bytes(src), bytes(dst)) + udp
    return b"\x01" * 6 + b"\x02" * 6 + b"\x08\x00" + ip


def pcap(path, packets):
    with open(path, "wb") as f:
        f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
        for t, frame in packets:
            sec = int(t)
            f.write(struct.pack("<IIII", sec, round((t - sec) * 1e6), len(frame), len(frame)) + frame)


def main():
    d = sys.argv[1]
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "radars.json"), "w") as f:
        json.dump({"radars": [{"name": "north", "sac": 25, "sic": 10, "lat_deg": 45.5, "lon_deg": 16.0,
                               "h_m": 150.0}]}, f)
    packets, stream, truth = [], b"", []
    for k in range(12):
        t = T0 + k
        reports = [(10, cat048(10, t, 60 + 0.1 * k, (359.5 + 0.2 * k) % 360, 250, 25000)),
                   (11, cat048(11, t + 0.25, 80 - 0.1 * k, 90 + k, 250))]
        for sic, r in reports:
            b = block(48, [r])
            stream += b
            # Captured 0.3 s after the report's time, on both feeds.
            tt = t + (0.25 if sic == 11 else 0) + 0.3
            packets.append((tt, udp_frame([10, 0, 0, 1], [232, 1, 1, 1], 20001, 21001, b)))
            packets.append((tt + 0.0001, udp_frame([10, 0, 0, 2], [232, 2, 1, 1], 20002, 22001, b)))
        truth.append((t - EPOCH, "north"))
        truth.append((t + 0.25 - EPOCH, "25-11"))
        if k % 4 == 0:
            n = block(34, [cat034_north(10, t + 0.5)])
            packets.append((t + 0.6, udp_frame([10, 0, 0, 1], [232, 1, 1, 2], 20001, 21002, n)))
    pcap(os.path.join(d, "feed.pcap"), packets)
    with open(os.path.join(d, "feed.ast"), "wb") as f:
        f.write(stream)
    with open(os.path.join(d, "truth.csv"), "w") as f:
        f.write("t_s,radar\n")
        for t, name in sorted(truth):
            f.write(f"{t:.7f},{name}\n")
    bad_block = b"\x30\x00\xff" + b"\x00" * 10
    spare = block(1, [record({1: bytes([25, 10]), 2: bytes([0x20]), 16: b""})])
    pcap(os.path.join(d, "bad.pcap"), packets[:2] + [(T0 + 0.5, udp_frame([10, 0, 0, 1], [232, 1, 1, 1], 20001, 21001, bad_block)),
                                                      (T0 + 0.6, udp_frame([10, 0, 0, 1], [232, 1, 1, 1], 20001, 21001, spare))])


if __name__ == "__main__":
    main()
