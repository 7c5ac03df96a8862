#!/usr/bin/env bash
# CLI test export_cli_data: registered, and described, in tests/cli/rk_export.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/export; rm -rf "$d"; mkdir -p "$d"
rk-sim multistation --out "$d/trial" --stations 3 --duration 5 --range-stations 1 --seed 3 --quiet
rk-intersect --stations "$d/trial/stations.json" -o "$d/traj.csv" -q
python3 - "$d" <<'PY'
import csv, sys
d = sys.argv[1]
lines = [l for l in open(d + "/traj.csv") if not l.startswith("#")]
rows = list(csv.DictReader(lines))
assert sum(r["status"] == "ok" for r in rows) > 100, "the trajectory should be mostly ok"
# Two ids: 'nose' is the trajectory; 'tail' 0.0001 deg north, 3 m lower, with every 40th row lost (runs split there).
cols = ["t_s", "id"] + [c for c in rows[0] if c != "t_s"]
with open(d + "/ids.csv", "w", newline="") as f:
    w = csv.DictWriter(f, cols, extrasaction="ignore")
    w.writeheader()
    for k, r in enumerate(rows):
        w.writerow(dict(r, id="nose"))
        t = dict(r, id="tail")
        if r["status"] == "ok" and k % 40 == 20:
            for c in ("e_m", "n_m", "u_m", "lat_deg", "lon_deg", "h_m", "sigma_e_m", "sigma_n_m", "sigma_u_m"):
                t[c] = ""
            t["status"] = "lost"
        elif t["lat_deg"]:
            t["lat_deg"] = "%.9f" % (float(t["lat_deg"]) + 1e-4)
            t["h_m"] = "%.4f" % (float(t["h_m"]) - 3.0)
        w.writerow(t)
# A located target with its station's WGS-84 columns (as rk-locate --station writes them): the trajectory's
# positions; every 25th row without a range, so without a position (the line must not bridge it).
loc = ["t_s", "az_deg", "el_deg", "range_m", "e_m", "n_m", "u_m", "status", "sigma_az_deg", "sigma_el_deg",
       "sigma_range_m", "sigma_e_m", "sigma_n_m", "sigma_u_m", "lat_deg", "lon_deg", "h_m"]
with open(d + "/located.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(loc)
    for k, r in enumerate(rows):
        if r["status"] != "ok":
            continue
        has = k % 25 != 7
        pos = [r[c] for c in ("e_m", "n_m", "u_m")] if has else ["", "", ""]
        sig = [r[c] for c in ("sigma_e_m", "sigma_n_m", "sigma_u_m")] if has else ["", "", ""]
        geo = [r[c] for c in ("lat_deg", "lon_deg", "h_m")] if has else ["", "", ""]
        w.writerow([r["t_s"], "55.0", "1.0", "12000.0" if has else ""] + pos + ["ok", "0.0014", "0.0014", "1.0" if has else ""] + sig + geo)
PY
echo ok
