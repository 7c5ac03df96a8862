#!/usr/bin/env bash
# Beacon-chain benchmark for issue 2: accuracy, tracking and speed figures, measured on
# rk-sim trials with truth. Writes everything under OUT (default /tmp/rk-beacon-bench) and
# prints a Markdown summary (also OUT/summary.md) for docs/benchmarks.md.
#   bench/beacon_bench.sh [OUT]        needs a Release build in build/ (scripts/setup.sh)
# Environment: FRAMES_SPEED (default 200) frames of 2448x2048 video for the speed test.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=$ROOT/build/apps
OUT=${1:-/tmp/rk-beacon-bench}
FRAMES_SPEED=${FRAMES_SPEED:-200}
STATS="python3 $ROOT/bench/beacon_track_stats.py"
mkdir -p "$OUT"
S=$OUT/summary.md
: > "$S"
say() { echo "$*" | tee -a "$S"; }
jget() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

say "## Beacon chain (issue 2) — $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
say ""

# 1. Static centroid: default camera, target fixed, 100 frames; three seeds (three sub-pixel positions).
say "### Centroid, static scene (default camera 2448x2048, peak 200 DN, read noise 2 DN, 8-bit, 100 frames per seed)"
say "| seed | x bias (px) | x std (px) | y bias (px) | y std (px) |"
say "|---|---|---|---|---|"
for seed in 1 2 3; do
  d=$OUT/static_$seed
  $B/rk-sim beacon --out "$d" --force --trajectory static --duration 5 --seed $seed --turret-lag-s 0 --jitter-arcsec 0 --turret-noise-deg 0 --quiet
  $B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --quiet
  $STATS "$d/track.csv" "$d/truth/beacon.csv" > "$d/stats.json"
  say "| $seed | $(jget $d/stats.json "'%.4f'%d['x_error_px']['mean']") | $(jget $d/stats.json "'%.4f'%d['x_error_px']['std']") | $(jget $d/stats.json "'%.4f'%d['y_error_px']['mean']") | $(jget $d/stats.json "'%.4f'%d['y_error_px']['std']") |"
done
say ""

# 2. Moving scene + angles + range + speed: default trajectory, default camera, no turret noise.
d=$OUT/moving
say "### Moving scene, default trajectory, default camera, turret noise 0 ($FRAMES_SPEED frames)"
dur=$(python3 -c "print($FRAMES_SPEED/20)")
$B/rk-sim beacon --out "$d" --force --duration "$dur" --seed 11 --turret-noise-deg 0 --quiet
$STATS "$d/track.csv" "$d/truth/beacon.csv" > /dev/null 2>&1 || true
/usr/bin/time -f "%e %U %S" -o "$d/time_decode.txt" $B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" --decode-only -o "$d/decode.csv" --quiet
/usr/bin/time -f "%e %U %S" -o "$d/time_extract.txt" $B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --quiet
/usr/bin/time -f "%e %U %S" -o "$d/time_decode2.txt" $B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" --decode-only -o "$d/decode.csv" --quiet
$STATS "$d/track.csv" "$d/truth/beacon.csv" --skip-frames 5 > "$d/stats.json"
$B/rk-locate --track "$d/track.csv" --camera "$d/az/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" -o "$d/located.csv" --quiet
$B/rk-analyze compare --estimate "$d/located.csv" --reference "$d/truth/target.csv" --columns az_deg,el_deg,range_m --arcsec -o "$d/compare.json" --quiet
say "- centroid error: x rms $(jget $d/stats.json "'%.4f'%d['x_error_px']['rms']") px, y rms $(jget $d/stats.json "'%.4f'%d['y_error_px']['rms']") px (n = $(jget $d/stats.json "d['x_error_px']['n']"))"
say "- azimuth error: rms $(jget $d/compare.json "'%.3f'%d['columns']['az_deg']['rms']")″, elevation rms $(jget $d/compare.json "'%.3f'%d['columns']['el_deg']['rms']")″ (n = $(jget $d/compare.json "d['columns']['az_deg']['n']"))"
say "- range at frame times: rms $(jget $d/compare.json "'%.3f'%(1000*d['columns']['range_m']['rms'])") mm, max |e| $(jget $d/compare.json "'%.3f'%(1000*max(abs(d['columns']['range_m']['max']),abs(d['columns']['range_m']['min'])))") mm (n = $(jget $d/compare.json "d['columns']['range_m']['n']"), device noise 0.35 mm)"
td=$(cut -d' ' -f1 "$d/time_decode.txt"); td2=$(cut -d' ' -f1 "$d/time_decode2.txt"); te=$(cut -d' ' -f1 "$d/time_extract.txt")
say "- speed on $FRAMES_SPEED frames of 2448x2048 8-bit FFV1: decode only ${td} s / ${td2} s (two runs around), extraction ${te} s, ratio $(python3 -c "print('%.3f'%($te/min($td,$td2)))")"
say ""

# 3. High elevation: overhead pass to 80 degrees.
d=$OUT/overhead
$B/rk-sim beacon --out "$d" --force --trajectory overhead --max-el-deg 80 --duration 10 --seed 12 --turret-noise-deg 0 --quiet
$B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --quiet
$B/rk-locate --track "$d/track.csv" --camera "$d/az/camera.json" --turret "$d/turret.csv" --range "$d/range.csv" -o "$d/located.csv" --quiet
$B/rk-analyze compare --estimate "$d/located.csv" --reference "$d/truth/target.csv" --columns az_deg,el_deg --arcsec -o "$d/compare.json" --quiet
maxel=$(python3 -c "import csv; print('%.1f'%max(float(r['el_deg']) for r in csv.DictReader(l for l in open('$d/truth/target.csv') if not l.startswith('#'))))")
say "### Overhead pass (max elevation ${maxel}°, default camera, turret noise 0)"
say "- azimuth error rms $(jget $d/compare.json "'%.3f'%d['columns']['az_deg']['rms']")″, elevation rms $(jget $d/compare.json "'%.3f'%d['columns']['el_deg']['rms']")″"
say ""

# 4. Tracking through occlusions with distractors (small camera to keep the run short).
say "### Tracking: occlusions and distractors (640x512, 4 glints, some brighter than the beacon)"
say "| occlusion | visible frames | tracked | ok | false frames | re-acquired after (frames) |"
say "|---|---|---|---|---|---|"
for occ in "2:0.5" "2:5"; do
  d=$OUT/occl_${occ/:/_}
  $B/rk-sim beacon --out "$d" --force --preset small --duration 12 --seed 21 --distractors 4 --occlusion "$occ" --quiet
  $B/rk-extract beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" -o "$d/track.csv" --quiet
  $STATS "$d/track.csv" "$d/truth/beacon.csv" > "$d/stats.json"
  say "| ${occ#*:} s at ${occ%%:*} s | $(jget $d/stats.json "d['visible']") | $(jget $d/stats.json "'%.2f %%'%(100*d['tracked_fraction'])") | $(jget $d/stats.json "'%.2f %%'%(100*d['ok_fraction'])") | $(jget $d/stats.json "d['false_frames']") | $(jget $d/stats.json "d['reacquire_delays']") |"
done
say ""
echo "summary: $S" >&2
