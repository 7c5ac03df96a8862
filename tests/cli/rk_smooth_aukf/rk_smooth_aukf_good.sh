#!/usr/bin/env bash
# CLI test rk_smooth_aukf_good: registered, and described, in tests/cli/rk_smooth_aukf.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/aukf; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-smooth aukf -i "$d/in.csv" --columns yaw_deg,x_m --smooth --derivatives --sigmas -o "$o/out.csv" \
  --report "$o/rep.json" 2> "$o/err.txt"
head -1 "$o/out.csv" | grep -qx 't_s,kind,yaw_deg,x_m,status,yaw_rate_deg_s,yaw_accel_deg_s2,x_rate_m_s,x_accel_m_s2,yaw_sigma_deg,x_sigma_m'
grep -q 'warning: 1 sample rows without any value' "$o/err.txt"
python3 - "$o/out.csv" "$o/rep.json" <<'EOF'
import csv, json, sys, math
rows = list(csv.DictReader(open(sys.argv[1])))
kinds = [r['kind'] for r in rows]
assert kinds.count('estimate') == 60 and kinds.count('prediction') == 59 and kinds.count('smoothed') == 119, kinds[:6]
t = [float(r['t_s']) for r in rows]
assert all(b >= a for a, b in zip(t, t[1:])), 'rows not in time order'
pred = [r for r in rows if r['kind'] == 'prediction']
assert abs(float(pred[0]['t_s']) - 0.025) < 1e-9, pred[0]
est = [r for r in rows if r['kind'] == 'estimate']
assert est[20]['status'] == 'predicted' and est[30]['status'] == 'ok' and est[21]['status'] == 'ok'
for r in rows:  # yaw written in [0, 360) (yaw-like name); truth 350 + 10 t through north
    y = float(r['yaw_deg']); assert 0 <= y < 360, y
    tr = (350 + 10 * float(r['t_s'])) % 360
    e = (y - tr + 180) % 360 - 180
    if float(r['t_s']) > 0.5: assert abs(e) < 0.2, (r, e)
    if float(r['t_s']) > 0.5: assert abs(float(r['yaw_rate_deg_s']) - 10) < 2, r
rep = json.load(open(sys.argv[2]))
for k in ('tool', 'version', 'command_line', 'inputs', 'options', 'counts', 'final_Q', 'final_R', 'nis_mean'):
    assert k in rep, k
c = rep['counts']
assert c['samples'] == 60 and c['updates'] == 58 and c['skipped_updates'] == 1 and c['partial_updates'] == 1, c
for k in ('repairs_q', 'repairs_r', 'repairs_p'): assert k in c
assert len(rep['final_Q']) == 6 and len(rep['final_R']) == 2
o = rep['options']
assert o['noise_estimate'] == 'ml' and o['noise_fit'] == 'causal' and o['smooth_noise_fit'] == 'file', o
for col in o['columns']:  # σ and q estimated: q by maximum likelihood, reported with its search (last refit: 32 rows)
    ml = col['noise_ml']; assert ml['used'] and ml['evaluations'] > 30 and ml['innovations'] > 20, col
rows = [f['rows'] for f in rep['noise_refits']]  # causal refits: every row 16…31, then 32 (60 rows in all)
assert rows == list(range(16, 33)), rows
assert all(f['restarted'] and len(f['meas_sigma']) == 2 and len(f['q']) == 2 for f in rep['noise_refits'])
assert len(rep['smooth_noise']['meas_sigma']) == 2, rep.get('smooth_noise')
EOF
# --noise-estimate moments: no likelihood search
rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --noise-estimate moments -o "$o/mom.csv" --report "$o/mom.json" 2>/dev/null
python3 -c "import json; o=json.load(open('$o/mom.json'))['options']; assert o['noise_estimate']=='moments' and 'noise_ml' not in o['columns'][0], o"
# stdout, --lead, adaptation with fading memory, explicit noise in file units
rk-smooth aukf -i "$d/in.csv" --columns yaw_deg --lead 0.25 --adapt qr --fading 0.9 --meas-sigma 0.05 --q 100 -o - \
  --report "$o/rep2.json" > "$o/stdout.csv" 2>/dev/null
grep -q '^0.012500000,prediction,' "$o/stdout.csv"
python3 -c "import json,sys; r=json.load(open('$o/rep2.json')); o=r['options']; assert o['adapt']=='qr' and o['memory']=='fading' and abs(o['columns'][0]['meas_sigma']-0.05)<1e-12 and abs(o['columns'][0]['q']-100)<1e-9, o"
rk-smooth aukf --help | grep -q -- '--adapt'
