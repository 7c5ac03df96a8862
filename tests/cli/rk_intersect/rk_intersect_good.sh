#!/usr/bin/env bash
# CLI test rk_intersect_good: registered, and described, in tests/cli/rk_intersect.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/intersect; t=$d/trial; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-intersect --stations "$t/stations.json" -o "$o/traj.csv" --report "$o/report.json" --quiet
head -1 "$o/traj.csv" | grep -q '^t_s,e_m,n_m,u_m,lat_deg,lon_deg,h_m,sigma_e_m,sigma_n_m,sigma_u_m,n_stations,status,rms_residual_arcsec,'
head -1 "$o/traj.csv" | grep -q ',s1_range_res_m,s1_los,s2_az_res_arcsec,'
# One row per distinct station row time (truth.csv is written at the same union).
test "$(grep -c '' "$o/traj.csv")" = "$(grep -c '' "$t/truth.csv")"
grep -q '"tool": "rk-intersect"' "$o/report.json"
grep -q '"median_rho_en"' "$o/report.json"
# Error against truth within 5 σ on every ok row, and most rows ok.
python3 - "$o/traj.csv" "$t/truth.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
truth = {r["t_s"]: r for r in csv.DictReader(open(sys.argv[2]))}
ok = [r for r in rows if r["status"] == "ok"]
assert len(ok) > 0.9 * len(rows), (len(ok), len(rows))
for r in ok:
    tr = truth[r["t_s"]]
    for c in "enu":
        err = float(r[c + "_m"]) - float(tr[c + "_m"])
        assert abs(err) < 5 * float(r["sigma_%s_m" % c]) + 1e-3, (r["t_s"], c, err, r["sigma_%s_m" % c])
print("rows", len(rows), "ok", len(ok))
PY
# --at and --smooth; stdout.
rk-intersect --stations "$t/stations.json" --at "$d/times.csv" --smooth -o - --quiet >"$o/at.csv"
test "$(grep -c '' "$o/at.csv")" = 4
head -1 "$o/at.csv" | grep -q ',ve_mps,vn_mps,vu_mps,sigma_ve_mps,'
grep -q '^2.000000000,' "$o/at.csv"
# --rate grid.
rk-intersect --stations "$t/stations.json" --rate 10 -o "$o/rate.csv" --quiet
grep -q '^0.100000000,' "$o/rate.csv"
grep -q '^4.900000000,' "$o/rate.csv"
echo ok
