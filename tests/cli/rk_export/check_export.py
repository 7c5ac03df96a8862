#!/usr/bin/env python3
"""Checks rk-export's KML and CZML against the CSV they were made from (issue 34's targets), written from the
formats' specifications, not from rangekit's code.

  check_export.py CSV [--kml FILE] [--czml FILE] [--epoch ISO] [--sample-interval S] [--geoid M]

The rows placed are those whose status has values (ok, reacquired, predicted) and that have lat_deg, lon_deg,
h_m; a path per id (one without an id column); a run is a stretch of placed rows of one id with no unplaced row
of that id between them.
KML (OGC KML 2.2): a kml root in the KML 2.2 namespace holding one Document; per path a Folder whose LineStrings
hold, in order, every placed row of each run of two or more rows, and whose Points (in a "samples" Folder) hold
placed rows found by their SimpleData t_s; coordinates lon,lat,alt equal the CSV's lon_deg, lat_deg to 1e-7 deg
and h_m - geoid to 1 µm; altitudeMode absolute; with an epoch each Point has TimeStamp/when = epoch + t_s (1 µs).
CZML (CZML Guide, "Packet"): a JSON array; its first packet has id "document" and version "1.0"; every packet an
object with a string id, ids unique; per path a packet with position.epoch ISO-8601 UTC, cartographicDegrees an
array of 4·n numbers [t, lon, lat, h, ...] with t increasing, equal to the CSV's placed rows (t = t_s to 1e-9 s,
degrees to 1e-7, h to 1 µm); availability an ISO-8601 interval or array of them, one per run, START <= STOP;
properties sigma_*_m as {"epoch", "number": [t, v, ...]} with 2·n numbers where given.
"""
import argparse
import csv
import datetime
import json
import math
import re
import sys
import xml.etree.ElementTree as ET

DEG_TOL = 1e-7       # the target
H_TOL = 1e-6         # heights written to the micrometre
T_TOL = 1e-9         # t_s written with 9 decimals
WHEN_TOL_S = 1e-6    # absolute times to the microsecond
KML_NS = "{http://www.opengis.net/kml/2.2}"
ISO = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?Z$")
PLACED = ("ok", "reacquired", "predicted")


def iso_seconds(text):
    assert ISO.match(text), "not ISO-8601 UTC: %r" % text
    base, _, frac = text[:-1].partition(".")
    t = datetime.datetime.strptime(base, "%Y-%m-%dT%H:%M:%S").replace(tzinfo=datetime.timezone.utc)
    return t.timestamp() + (float("0." + frac) if frac else 0.0)


def wrap(lon):
    return lon if -180.0 <= lon < 180.0 else lon - 360.0 * math.floor((lon + 180.0) / 360.0)


def read_paths(path):
    """{id: [runs]} with each run a list of (t, lat, lon, h, row) of placed rows."""
    rows = list(csv.DictReader(line for line in open(path, encoding="utf-8") if not line.startswith("#")))
    paths = {}
    for r in rows:
        pid = r.get("id", "")
        runs = paths.setdefault(pid, [[]])
        placed = r.get("status", "ok") in PLACED and all(r.get(c, "") != "" for c in ("lat_deg", "lon_deg", "h_m"))
        if placed:
            runs[-1].append((float(r["t_s"]), float(r["lat_deg"]), wrap(float(r["lon_deg"])), float(r["h_m"]), r))
        elif runs[-1]:
            runs.append([])
    return {k: [run for run in v if run] for k, v in paths.items()}


def close(a, b, tol, what):
    assert abs(a - b) <= tol, "%s: %r vs %r (tolerance %g)" % (what, a, b, tol)


def check_kml(path, paths, epoch, geoid):
    root = ET.parse(path).getroot()
    assert root.tag == KML_NS + "kml", root.tag
    docs = root.findall(KML_NS + "Document")
    assert len(docs) == 1
    folders = [f for f in docs[0].findall(KML_NS + "Folder")]
    placed_ids = [k for k, runs in paths.items() if runs]
    assert len(folders) == len(placed_ids), (len(folders), placed_ids)
    n_coords = 0
    for folder, pid in zip(folders, placed_ids):
        name = folder.findtext(KML_NS + "name")
        assert pid == "" or name == pid, (name, pid)
        runs = [run for run in paths[pid] if len(run) >= 2]
        lines = folder.findall(KML_NS + "Placemark/" + KML_NS + "LineString")
        assert len(lines) == len(runs), (len(lines), len(runs))
        for line, run in zip(lines, runs):
            assert line.findtext(KML_NS + "altitudeMode") == "absolute"
            coords = line.findtext(KML_NS + "coordinates").split()
            assert len(coords) == len(run), (len(coords), len(run))
            for c, (t, lat, lon, h, _) in zip(coords, run):
                x, y, z = (float(v) for v in c.split(","))
                close(x, lon, DEG_TOL, "KML line lon at t_s %g" % t)
                close(y, lat, DEG_TOL, "KML line lat at t_s %g" % t)
                close(z, h - geoid, H_TOL, "KML line altitude at t_s %g" % t)
                n_coords += 1
        by_t = {round(s[0], 6): s for run in paths[pid] for s in run}
        points = folder.findall(KML_NS + "Folder/" + KML_NS + "Placemark")
        assert points, "no sample Placemark"
        for pm in points:
            t = float(pm.find(".//%sSimpleData[@name='t_s']" % KML_NS).text)
            s = by_t[round(t, 6)]
            x, y, z = (float(v) for v in pm.findtext(".//%scoordinates" % KML_NS).split(","))
            close(x, s[2], DEG_TOL, "KML point lon")
            close(y, s[1], DEG_TOL, "KML point lat")
            close(z, s[3] - geoid, H_TOL, "KML point altitude")
            when = pm.findtext(KML_NS + "TimeStamp/" + KML_NS + "when")
            if epoch is None:
                assert when is None, "a TimeStamp without an epoch"
            else:
                close(iso_seconds(when), epoch + t, WHEN_TOL_S, "KML when")
            n_coords += 1
    return n_coords


def check_czml(path, paths, epoch):
    doc = json.load(open(path, encoding="utf-8"))
    assert isinstance(doc, list) and doc, "CZML is a JSON array of packets"
    assert doc[0].get("id") == "document" and doc[0].get("version") == "1.0", doc[0]
    ids = [p.get("id") for p in doc]
    assert all(isinstance(i, str) and i for i in ids) and len(set(ids)) == len(ids), ids
    interval = doc[0]["clock"]["interval"].split("/")
    assert iso_seconds(interval[0]) <= iso_seconds(interval[1])
    placed_ids = [k for k, runs in paths.items() if runs]
    assert len(doc) == 1 + len(placed_ids), (len(doc), placed_ids)
    n = 0
    for packet, pid in zip(doc[1:], placed_ids):
        assert packet["id"] == ("trajectory" if pid == "" else "trajectory/" + pid), packet["id"]
        pos = packet["position"]
        e = iso_seconds(pos["epoch"])
        if epoch is not None:
            close(e, epoch, WHEN_TOL_S, "CZML epoch")
        deg = pos["cartographicDegrees"]
        samples = [s for run in paths[pid] for s in run]
        assert isinstance(deg, list) and len(deg) == 4 * len(samples), (len(deg), len(samples))
        assert all(isinstance(v, (int, float)) for v in deg)
        times = deg[0::4]
        assert all(b > a for a, b in zip(times, times[1:])), "CZML sample times must increase"
        for k, (t, lat, lon, h, _) in enumerate(samples):
            close(deg[4 * k], t, T_TOL, "CZML t")
            close(deg[4 * k + 1], lon, DEG_TOL, "CZML lon at t_s %g" % t)
            close(deg[4 * k + 2], lat, DEG_TOL, "CZML lat at t_s %g" % t)
            close(deg[4 * k + 3], h, H_TOL, "CZML height at t_s %g" % t)
            n += 1
        avail = packet["availability"]
        avail = [avail] if isinstance(avail, str) else avail
        assert len(avail) == len(paths[pid]), (len(avail), len(paths[pid]))
        for a, run in zip(avail, paths[pid]):
            start, stop = (iso_seconds(x) for x in a.split("/"))
            assert start <= e + run[0][0] + 1e-9 and e + run[-1][0] - 1e-9 <= stop, (a, run[0][0], run[-1][0])
        for c in ("sigma_e_m", "sigma_n_m", "sigma_u_m"):
            given = [s for s in samples if s[4].get(c, "") != ""]
            if not given:
                continue
            prop = packet["properties"][c]
            iso_seconds(prop["epoch"])
            assert len(prop["number"]) == 2 * len(given), (c, len(prop["number"]), len(given))
            for k, s in enumerate(given):
                close(prop["number"][2 * k + 1], float(s[4][c]), 1e-4, c)
    return n


def main():
    ap = argparse.ArgumentParser(allow_abbrev=False)
    ap.add_argument("csv")
    ap.add_argument("--kml")
    ap.add_argument("--czml")
    ap.add_argument("--epoch")
    ap.add_argument("--geoid", type=float, default=0.0)
    a = ap.parse_args()
    paths = read_paths(a.csv)
    epoch = iso_seconds(a.epoch) if a.epoch else None
    if a.kml:
        print("KML: %d coordinates equal the CSV's" % check_kml(a.kml, paths, epoch, a.geoid))
    if a.czml:
        print("CZML: %d samples equal the CSV's" % check_czml(a.czml, paths, epoch))


if __name__ == "__main__":
    sys.exit(main())
