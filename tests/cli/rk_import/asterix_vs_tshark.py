#!/usr/bin/python3
"""Checks rk-import asterix's plots against Wireshark's own ASTERIX dissector (tshark), an independent decoder.

    asterix_vs_tshark.py CAPTURE.pcap PLOTS.csv EPOCH_UTC

Decodes CAPTURE with tshark (every UDP port of the capture decoded as ASTERIX; -T json with --no-duplicate-keys, or
a datagram's second block would replace its first), takes its CAT048 target reports that carry a position, and
compares them with PLOTS.csv (rk-import asterix's output for the same capture and epoch): every report tshark
decodes is in the plots exactly once (a redundant feed's copies are one report), with the same SAC/SIC, time of
day, rho, theta, flight level, track number, Mode 3/A and address, to the items' own resolution; and the plots
hold no other CAT048 report. (tshark's one mistake on CAT048 here, an unsigned flight level, is undone.) CAT001 is not compared: tshark 4.0 decodes CAT001 track records with the plot layout.
Exit 0 and a one-line summary when they agree; 1 with the differences.
"""
import csv
import datetime
import json
import subprocess
import sys


def as_list(x):
    return x if isinstance(x, list) else [x]


def signed14(quarters):
    """tshark 4.0 shows I048/090's 14-bit flight level as unsigned (FL 4095 for the code 0x3FFC); the
    specification makes it two's complement (FL -1): read it so."""
    return quarters - 16384 if quarters >= 8192 else quarters


def tshark_reports(capture):
    ports = set()
    out = subprocess.run(["tshark", "-r", capture, "-T", "fields", "-e", "udp.srcport", "-e", "udp.dstport"],
                         check=True, capture_output=True, text=True).stdout
    for line in out.split():
        if line.strip():
            ports.add(int(line))
    decode = []
    for p in sorted(ports):
        decode += ["-d", f"udp.port=={p},asterix"]
    js = subprocess.run(["tshark", "-r", capture, *decode, "-T", "json", "--no-duplicate-keys"],
                        check=True, capture_output=True, text=True).stdout
    reports = []
    for packet in json.loads(js):
        for block in as_list(packet["_source"]["layers"].get("asterix", [])):
            if block.get("asterix.category") != "48":
                continue
            for m in as_list(block.get("asterix.message", [])):
                if "asterix.048_040" not in m:
                    continue
                src = m["asterix.048_010"]
                fl = m.get("asterix.048_090")
                m3 = m.get("asterix.048_070")
                reports.append((
                    int(src["asterix.048_010_SAC"], 16), int(src["asterix.048_010_SIC"], 16),
                    round(float(m["asterix.048_140"]["asterix.048_140_VALUE"]) * 128),
                    round(float(m["asterix.048_040"]["asterix.048_040_RHO"]) * 256),
                    round(float(m["asterix.048_040"]["asterix.048_040_THETA"]) / 360 * 65536) % 65536,
                    signed14(round(float(fl["asterix.048_090_FL"]) * 4))
                    if fl and fl["asterix.048_090_V"] == "0" and fl["asterix.048_090_G"] == "0" else None,
                    int(m["asterix.048_161"]["asterix.048_161_TRN"]) if "asterix.048_161" in m else None,
                    int(m3["asterix.048_070_MODE3A"])
                    if m3 and m3["asterix.048_070_V"] == "0" and m3["asterix.048_070_G"] == "0" else None,
                    int(m["asterix.048_220"]["asterix.048_220_VALUE"], 16) if "asterix.048_220" in m else None,
                ))
    return reports


def plot_reports(plots, epoch_utc):
    epoch = datetime.datetime.fromisoformat(epoch_utc.replace("Z", "+00:00")).timestamp()
    reports = []
    with open(plots) as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            tod = (float(row["t_s"]) + epoch) % 86400
            reports.append((
                int(row["sac"]), int(row["sic"]), round(tod * 128) % (86400 * 128),
                round(float(row["range_m"]) / 1852 * 256), round(float(row["az_deg"]) / 360 * 65536) % 65536,
                round(float(row["flight_level"]) * 4) if row["flight_level"] else None,
                int(row["track_id"]) if row["track_id"] else None,
                int(row["mode3a"], 8) if row["mode3a"] else None,
                int(row["address"], 16) if row["address"] else None,
            ))
    return reports


def main():
    capture, plots, epoch_utc = sys.argv[1:4]
    theirs = tshark_reports(capture)
    ours = plot_reports(plots, epoch_utc)
    unique = set(theirs)
    problems = []
    for r in sorted(unique - set(ours)):
        problems.append(f"tshark decodes {r} (sac, sic, tod*128, rho*256, theta*2^16/360, fl*4, track, mode3a, address); "
                        "the plots do not have it")
    for r in sorted(set(ours) - unique):
        problems.append(f"the plots have {r}; tshark decodes no such report")
    counts = {}
    for r in ours:
        counts[r] = counts.get(r, 0) + 1
    for r, n in counts.items():
        if n > 1:
            problems.append(f"the plots have {r} {n} times")
    if problems:
        print("\n".join(problems[:40]))
        print(f"{len(problems)} differences ({len(theirs)} tshark reports, {len(unique)} distinct; {len(ours)} plots)")
        return 1
    print(f"agree: {len(unique)} distinct CAT048 reports ({len(theirs)} with the redundant copies) = {len(ours)} plots")
    return 0


if __name__ == "__main__":
    sys.exit(main())
