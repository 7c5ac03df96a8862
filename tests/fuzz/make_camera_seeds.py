#!/usr/bin/python3
"""Writes the seed corpus of fuzz_cine, fuzz_mraw and fuzz_y4m (small synthetic files of every packing and
header form; the real files of ../shared/data/real are never copied here); its writers (cine, cihx, cih, mraw, y4m)
are also imported by the CLI tests' and the benchmark's recordings. Run from the repository root:
    /usr/bin/python3 tests/fuzz/make_camera_seeds.py
"""
import os
import random
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def pack_bits(values, bits):
    out, acc, n = bytearray(), 0, 0
    for v in values:
        acc = (acc << bits) | v
        n += bits
        while n >= 8:
            n -= 8
            out.append((acc >> n) & 0xFF)
    if n:
        out.append((acc << (8 - n)) & 0xFF)
    return bytes(out)


def cine(width, height, bit_count, compression, file_compression=0, cfa=0, n=2, stamps=True, seed=1, stamp_list=None):
    """A CINE of n random frames; stamps: a time block of n stamps 1 ms apart from 1700000000 s UTC (IRIG flag 0), or
    stamp_list's (seconds << 32 | fractions) each."""
    if stamp_list is not None:
        n = len(stamp_list)
    rnd = random.Random(seed)
    bits = {256: 10, 1024: 12}.get(compression, bit_count)
    frames = []
    for _ in range(n):
        vals = [rnd.randrange(1 << min(bits, 12)) for _ in range(width * height)]
        if bits in (8, 16):
            rows = [vals[r * width:(r + 1) * width] for r in range(height)]
            if compression == 0:
                rows = rows[::-1]  # bottom-up
            fmt = "<%d%s" % (width, "B" if bits == 8 else "H")
            frames.append(b"".join(struct.pack(fmt, *r) for r in rows))
        else:
            frames.append(pack_bits(vals, bits))
    setup_len = 1600
    tags = b""
    if stamps:
        t = stamp_list if stamp_list is not None else [(1700000000 << 32) | ((i * 4294967) & ~3) for i in range(n)]
        tags += struct.pack("<IHH", 8 + 8 * n, 1002, 0) + b"".join(struct.pack("<Q", x) for x in t)
        tags += struct.pack("<IHH", 8 + 4 * n, 1003, 0) + b"".join(struct.pack("<I", 4294967) for _ in range(n))
    off_setup = 84
    off_offsets = off_setup + setup_len + len(tags)
    head = struct.pack("<HHHHiIiIIIIII", 0x4943, 44, file_compression, 1, -1, n, -1, n, 44, off_setup, off_offsets,
                       0, 1700000000)
    bmp = struct.pack("<IiiHHIIiiII", 40, width, height, 1, bit_count, compression, len(frames[0]), 0, 0, 0, 0)
    setup = bytearray(setup_len)
    struct.pack_into("<HH", setup, 140, 0x5453, setup_len)
    struct.pack_into("<I", setup, 768, 1000)
    struct.pack_into("<I", setup, 808, cfa)
    struct.pack_into("<I", setup, 896, 12 if bit_count == 16 else 8)
    struct.pack_into("<I", setup, 1568, 500000)
    body = head + bmp + bytes(setup) + tags
    at = off_offsets + 8 * n
    offsets, images = b"", b""
    for f in frames:
        offsets += struct.pack("<Q", at + len(images))
        images += struct.pack("<II", 8, len(f)) + f
    return body + offsets + images


def cihx(width, height, bits, total):
    pre = b"!!! This file can not be edited. !!!".ljust(0x100, b"\0") + b"CIHX"
    pre = pre.ljust(0x13C, b"\0")
    xml = ('<?xml version="1.0" encoding="utf-8"?>\r\n<cih>\r\n<imageFileInfo><fileFormat>Mraw</fileFormat>'
           '</imageFileInfo>\r\n<imageDataInfo><resolution><width>%d</width><height>%d</height></resolution>'
           '<colorInfo><type>Mono</type><bit>%d</bit></colorInfo><effectiveBit><depth>12</depth><side>Lower</side>'
           '</effectiveBit></imageDataInfo>\r\n<frameInfo><totalFrame>%d</totalFrame><startFrame>5</startFrame>'
           '<skipFrame>1</skipFrame></frameInfo>\r\n<recordInfo><recordRate>30000</recordRate><shutterSpeedNsec>20000'
           '</shutterSpeedNsec></recordInfo>\r\n</cih>\r\n' % (width, height, bits, total))
    return pre + xml.encode() + b"\x01" * 16


def cih(width, height, bits, total):
    return ("#Camera Information Header\nRecord Rate(fps) : 60000\nShutter Speed(s) : 1/800000\nTotal Frame : %d\n"
            "Start Frame : 0\nImage Width : %d\nImage Height : %d\nColor Type : Mono\nColor Bit : %d\n"
            "File Format : MRaw\nEffectiveBit Depth : 12\nEffectiveBit Side : Lower\n\n" % (total, width, height, bits)).encode()


def mraw(width, height, bits, total, seed=2):
    rnd = random.Random(seed)
    vals = [rnd.randrange(1 << min(bits, 12)) for _ in range(width * height * total)]
    if bits == 12:
        return pack_bits(vals, 12)
    return struct.pack("<%d%s" % (len(vals), "B" if bits == 8 else "H"), *vals)


def y4m(width, height, depth, frames, seed=3):
    rnd = random.Random(seed)
    out = b"YUV4MPEG2 W%d H%d F20:1 Ip A1:1 C%s\n" % (width, height, b"mono16" if depth == 16 else b"mono")
    for _ in range(frames):
        out += b"FRAME\n" + bytes(rnd.randrange(256) for _ in range(width * height * (2 if depth == 16 else 1)))
    return out


def write(harness, name, data):
    d = os.path.join(ROOT, harness)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def main():
    write("fuzz_cine", "u8_bottom_up.cine", cine(8, 4, 8, 0))
    write("fuzz_cine", "u16_time_exposure.cine", cine(8, 4, 16, 0))
    write("fuzz_cine", "p10_bayer_gbrg.cine", cine(8, 4, 16, 256, file_compression=2, cfa=3))
    write("fuzz_cine", "p12_no_time_block.cine", cine(8, 4, 16, 1024, stamps=False))
    for bits in (8, 12, 16):
        write("fuzz_mraw", "cihx_%d" % bits, b"\0" + cihx(6, 4, bits, 2) + b"\n=====\n" + mraw(6, 4, bits, 2))
    write("fuzz_mraw", "cih_12", b"\1" + cih(6, 4, 12, 2) + b"\n=====\n" + mraw(6, 4, 12, 2))
    write("fuzz_y4m", "mono8.y4m", y4m(8, 4, 8, 2))
    write("fuzz_y4m", "mono16.y4m", y4m(8, 4, 16, 2))
    write("fuzz_y4m", "torn_last_frame.y4m", y4m(8, 4, 8, 2)[:-5])


if __name__ == "__main__":
    main()
