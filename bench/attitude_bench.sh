#!/usr/bin/env bash
# Attitude-chain benchmark for issue 4 (seed 001): rk-sim attitude → rk-extract features →
# rk-attitude oi → rk-analyze compare, at seed 001's dynamic-test geometry (target 22 m → 16 m
# → 21 m, yaw 10°, pitch 7°, roll 5° on the way in and back, 100 mm attitude camera 2448×2048
# 3.45 µm on the tracking turret, 20 fps, 22 s = 440 frames), plus the random-problem comparison
# of the OI solver with OpenCV (attitude_pnp_bench). Prints a Markdown summary (OUT/summary.md).
#   bench/attitude_bench.sh [OUT]       needs a Release build in build/ (scripts/setup.sh)
# Environment: SEEDS (default "1 2"), KEEP_VIDEO=1 keeps the ~1 GB videos, PNP_PROBLEMS
# (default 10000), SKIP_PNP=1 / SKIP_VIDEO=1 skip a part.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=$ROOT/build/apps
OUT=${1:-/tmp/rk-attitude-bench}
SEEDS=${SEEDS:-"1 2"}
PNP_PROBLEMS=${PNP_PROBLEMS:-10000}
mkdir -p "$OUT"
S=$OUT/summary.md
: > "$S"
say() { echo "$*" | tee -a "$S"; }
jget() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

say "## Attitude chain (issue 4) — $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
say ""
if [ "${SKIP_PNP:-0}" != 1 ]; then
  say "### OI solver vs OpenCV on $PNP_PROBLEMS random problems per geometry (4–12 points, 0.1–1 px)"
  say '```'
  "$ROOT/build/bench/attitude_pnp_bench" --problems "$PNP_PROBLEMS" --repeats 3 \
    --methods oi,oi-pure,sqpnp-lm,sqpnp,iterative,epnp-lm,ippe-lm | tee -a "$S"
  say '```'
  say ""
fi
[ "${SKIP_VIDEO:-0}" = 1 ] && exit 0

say "### Attitude from rendered video, seed 001 geometry (440 frames per seed)"
say "| seed | yaw std (°) | pitch std (°) | roll std (°) | yaw/pitch/roll max abs (°) | position rms e/n/u (mm) | marker rms x/y (px) | identity errors | frames ok | extract ms/frame | oi ms/frame |"
say "|---|---|---|---|---|---|---|---|---|---|---|"
for seed in $SEEDS; do
  d=$OUT/seed_$seed
  $B/rk-sim attitude --out "$d" --force --seed "$seed" --quiet --report "$d.sim.json"
  /usr/bin/time -f "%e" -o "$d.t_extract" $B/rk-extract features --video "$d/att/video.mkv" --frames "$d/att/frames.csv" \
    --target "$d/target.json" -o "$d/points.csv" --report "$d/extract.json" --quiet
  /usr/bin/time -f "%e" -o "$d.t_oi" $B/rk-attitude oi --points "$d/points.csv" --camera "$d/att/camera.json" \
    --target "$d/target.json" --turret "$d/turret.csv" -o "$d/pose.csv" --report "$d/oi.json" --quiet
  $B/rk-analyze compare --estimate "$d/pose.csv" --reference "$d/truth/pose.csv" \
    --columns yaw_deg,pitch_deg,roll_deg,e_m,n_m,u_m -o "$d/compare.json" --quiet
  python3 "$ROOT/bench/attitude_points_stats.py" "$d/points.csv" "$d/truth/points.csv" > "$d/points_stats.txt"
  c="d['columns']"
  maxabs="'%.4f / %.4f / %.4f' % tuple(max(abs(d['columns'][k]['max']), abs(d['columns'][k]['min'])) for k in ('yaw_deg','pitch_deg','roll_deg'))"
  pos="'%.2f / %.2f / %.2f' % tuple(1000*d['columns'][k]['rms'] for k in ('e_m','n_m','u_m'))"
  pts=$(awk '/rms/ {printf "%s / %s", $7, $14}' "$d/points_stats.txt")
  ide=$(awk '/identity errors/ {print $5}' "$d/points_stats.txt")
  ok=$(jget "$d/oi.json" "d['counts']['status']['ok'] + d['counts']['status']['reacquired']")
  te=$(python3 -c "print('%.0f' % (1000*$(cat $d.t_extract)/440))")
  to=$(python3 -c "print('%.2f' % (1000*$(cat $d.t_oi)/440))")
  say "| $seed | $(jget $d/compare.json "'%.5f'%$c['yaw_deg']['std']") | $(jget $d/compare.json "'%.5f'%$c['pitch_deg']['std']") | $(jget $d/compare.json "'%.5f'%$c['roll_deg']['std']") | $(jget $d/compare.json "$maxabs") | $(jget $d/compare.json "$pos") | $pts | $ide | $ok / 440 | $te | $to |"
  python3 - "$d/pose.csv" "$d/compare.json" >> "$d/sigma.txt" <<'EOF'
import csv, json, sys, math
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["sigma_yaw_deg"]]
c = json.load(open(sys.argv[2]))["columns"]
for k in ("yaw", "pitch", "roll"):
    s = sum(float(r[f"sigma_{k}_deg"]) for r in rows) / len(rows)
    print(f"{k}: mean reported sigma {s:.5f} deg, measured std {c[k + '_deg']['std']:.5f} deg")
EOF
  [ "${KEEP_VIDEO:-0}" = 1 ] || rm -f "$d/att/video.mkv"
done
say ""
say "Reported 1σ (sigma_* columns, mean) against the measured error std:"
for seed in $SEEDS; do say "- seed $seed: $(tr '\n' ';' < "$OUT/seed_$seed/sigma.txt")"; done
