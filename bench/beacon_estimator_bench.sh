#!/usr/bin/env bash
# Centroid estimators on compact and sparse lamp clusters (issue 15 item 6): the cluster centroid
# (rk-extract beacon --estimator cluster) against the automatic choice (--estimator auto: per-lamp when
# the lamps resolve), static and moving, scored against rk-sim truth by bench/beacon_track_stats.py.
#   bench/beacon_estimator_bench.sh [OUT]        needs a Release build in build/
# Scenes (--preset small: 640x512, 3.45 um, 50 mm, 20 fps, 8-bit, lamps 160 DN, read noise 2 DN, 40 e-/DN):
#   compact: --cluster-span-m 0.03 (five lamps overlapping into one blob at 80 m)
#   sparse:  --cluster-span-m 0.1  (five separate spots 18 px across at 80 m)
#   static:  --trajectory static --duration 5 --turret-lag-s 0 --jitter-arcsec 0 (100 frames), seeds 1 2 3
#   moving:  default trajectory, --duration 10 (200 frames), seeds 1 2
# First 5 frames of each track skipped (the per-lamp flux shares settle). Prints a Markdown table.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
B=$ROOT/build/apps
OUT=${1:-/tmp/rk-beacon-estimator}
mkdir -p "$OUT"
jget() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
echo "| cluster | scene | seed | estimator | frames per-lamp | x bias | x std | y bias | y std | x rms | y rms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for span in 0.03 0.1; do
  name=$([ "$span" = 0.03 ] && echo compact || echo sparse)
  for scene in static moving; do
    if [ "$scene" = static ]; then
      seeds="1 2 3"
      sim=(--trajectory static --duration 5 --turret-lag-s 0 --jitter-arcsec 0 --turret-noise-deg 0)
    else
      seeds="1 2"
      sim=(--duration 10 --turret-noise-deg 0)
    fi
    for seed in $seeds; do
      d=$OUT/${name}_${scene}_$seed
      "$B/rk-sim" beacon --out "$d" --force --preset small --cluster-span-m "$span" --seed "$seed" "${sim[@]}" --quiet
      for est in cluster auto; do
        "$B/rk-extract" beacon --video "$d/az/video.mkv" --frames "$d/az/frames.csv" --estimator "$est" \
          -o "$d/track_$est.csv" --report "$d/report_$est.json" --quiet
        python3 "$ROOT/bench/beacon_track_stats.py" "$d/track_$est.csv" "$d/truth/beacon.csv" --skip-frames 5 \
          > "$d/stats_$est.json"
        s=$d/stats_$est.json
        echo "| $name | $scene | $seed | $est | $(jget "$d/report_$est.json" "d['centroid_estimator']['per_lamp']") |" \
          "$(jget "$s" "'%.4f'%d['x_error_px']['mean']") | $(jget "$s" "'%.4f'%d['x_error_px']['std']") |" \
          "$(jget "$s" "'%.4f'%d['y_error_px']['mean']") | $(jget "$s" "'%.4f'%d['y_error_px']['std']") |" \
          "$(jget "$s" "'%.4f'%d['x_error_px']['rms']") | $(jget "$s" "'%.4f'%d['y_error_px']['rms']") |"
      done
    done
  done
done
