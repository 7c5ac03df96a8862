#!/usr/bin/env bash
# Set-up (scripts/setup.sh), then the beacon measurement chain of seed 001 on the sample trial
# shipped in data/sample: rk-extract beacon → rk-locate → rk-analyze compare against the
# simulator's truth. Prints the error table; writes demo-out/ (track, located target, statistics,
# error series and a PNG of the azimuth/elevation error).
#   scripts/demo.sh [OUT]     (default OUT = demo-out in the repository)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
B=$ROOT/build/apps
D=$ROOT/data/sample
OUT=${1:-$ROOT/demo-out}
mkdir -p "$OUT"

echo "== rk-extract beacon: lamp cluster position in every frame"
"$B/rk-extract" beacon --video "$D/az/video.mkv" --frames "$D/az/frames.csv" -o "$OUT/track.csv" \
  --report "$OUT/extract_report.json"
python3 - "$OUT/track.csv" <<'PY'
import csv, collections, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
print("   frames:", len(rows), " status:", dict(collections.Counter(r['status'] for r in rows)))
PY
echo "== rk-locate: azimuth, elevation, range and ENU position at frame times"
"$B/rk-locate" --track "$OUT/track.csv" --camera "$D/az/camera.json" --turret "$D/turret.csv" \
  --range "$D/range.csv" -o "$OUT/located.csv" --report "$OUT/locate_report.json"
echo "== rk-analyze compare: located target against the simulator's truth (angles in arc-seconds)"
"$B/rk-analyze" compare --estimate "$OUT/located.csv" --reference "$D/truth/target.csv" \
  --columns az_deg,el_deg,range_m,e_m,n_m,u_m --arcsec --table --errors "$OUT/errors.csv" -o "$OUT/stats.json"
"$ROOT/scripts/rk-plot" -i "$OUT/errors.csv" --columns err_az_deg,err_el_deg --title "located - truth (sample trial), degrees" \
  -o "$OUT/azel_error.png"
echo "== wrote $OUT: track.csv located.csv stats.json errors.csv azel_error.png"
