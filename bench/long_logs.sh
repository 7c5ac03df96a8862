#!/usr/bin/env bash
# Issue 27 item 16: memory and speed of the CSV tools on a long turret log (docs/benchmarks.md
# "Issue 27 — long logs"). Generates the inputs (never committed): a turret log t_s,az_deg,el_deg at
# 1 kHz (ROWS rows, ≈ 41 bytes a row: 7.3 M rows ≈ 300 MB as in the trial), a beacon track and a
# frame-time list at 50 Hz over the same time, a camera. Then, per tool, peak RSS (/usr/bin/time -v,
# "Maximum resident set size") as a ratio to the largest input's size, and wall time; and the CSV
# parse speed (bench_csv, on the turret log in the page cache) as a ratio to `wc -l` on that file.
#   bench/long_logs.sh [ROWS] [WORKDIR] [BINDIR]
#   defaults: 7300000, /tmp/rk_long_logs, build/apps and build/bench of this checkout
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ROWS=${1:-7300000}
W=${2:-/tmp/rk_long_logs}
BIN=${3:-$ROOT/build/apps}
BENCH=${BENCH:-$ROOT/build/bench/bench_csv}
mkdir -p "$W"

gen() {
  # Turret at 1 kHz: a slow sweep with a little jitter, 8 decimals as encoders log them.
  awk -v n="$ROWS" 'BEGIN {
    print "t_s,az_deg,el_deg"
    for (i = 0; i < n; i++) {
      t = 1000 + i * 0.001
      printf "%.6f,%.10f,%.10f\n", t, 180 + 170 * sin(i * 1e-5) + 1e-4 * sin(i * 0.37), 20 + 15 * sin(i * 3e-6 + 1)
    }
  }' > "$W/turret.csv"
  # Beacon track and frame times at 50 Hz inside the turret log's span.
  awk -v n="$ROWS" 'BEGIN {
    print "frame,t_s,x_px,y_px,peak,area_px,status"
    m = int((n - 20) / 20)
    for (k = 0; k < m; k++) printf "%d,%.6f,%.4f,%.4f,200,12,ok\n", k, 1000.005 + 0.02 * k, 1223.5 + 30 * sin(k * 1e-3), 1023.5 + 20 * cos(k * 1e-3)
  }' > "$W/track.csv"
  awk -F, 'NR == 1 { print "frame,t_s"; next } { print $1 "," $2 }' "$W/track.csv" > "$W/at.csv"
  cat > "$W/camera.json" <<'EOF'
{"width_px": 2448, "height_px": 2048, "pixel_size_mm": [0.00345, 0.00345],
 "focal_length_mm": 50.0, "principal_point_px": [1223.5, 1023.5],
 "distortion": [-0.05, 0.01, 0.0001, -0.0001, 0], "mount_deg": {"yaw": 0.1, "pitch": -0.05, "roll": 0.2}}
EOF
}
if [ ! -s "$W/turret.csv" ] || [ "$(wc -l < "$W/turret.csv")" != "$((ROWS + 1))" ]; then gen; fi

size() { stat -c %s "$1"; }
echo "# rows $ROWS; turret.csv $(size "$W/turret.csv") bytes ($(awk -v b="$(size "$W/turret.csv")" -v n="$ROWS" 'BEGIN { printf "%.1f", b / n }') bytes a row), track.csv $(size "$W/track.csv") bytes; nproc $(nproc); load $(cut -d' ' -f1-3 /proc/loadavg)"

# measure NAME LARGEST_INPUT -- CMD...: peak RSS / size of LARGEST_INPUT, wall s.
measure() {
  local name=$1 big=$2
  shift 3
  /usr/bin/time -v "$@" 2> "$W/$name.time" > "$W/$name.stdout" || { echo "$name: failed"; tail -5 "$W/$name.time"; return 0; }
  local kb wall
  kb=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$W/$name.time")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ { print $2 }' "$W/$name.time")
  awk -v n="$name" -v kb="$kb" -v b="$(size "$big")" -v w="$wall" \
    'BEGIN { printf "%-26s peak RSS %7.0f MB = %.2f x largest input (%.0f MB); wall %s\n", n, kb / 1024, kb * 1024 / b, b / 1048576, w }'
}

cat "$W"/*.csv > "$W/warm.tmp"; rm -f "$W/warm.tmp"  # into the page cache
measure rk-locate "$W/turret.csv" -- "$BIN/rk-locate" -q --track "$W/track.csv" --camera "$W/camera.json" --turret "$W/turret.csv" -o "$W/located.csv"
measure rk-smooth-resample-at "$W/turret.csv" -- "$BIN/rk-smooth" resample -q -i "$W/turret.csv" --columns az_deg,el_deg --at "$W/at.csv" -o "$W/resampled.csv"
measure rk-smooth-singer "$W/turret.csv" -- "$BIN/rk-smooth" singer -q -i "$W/turret.csv" --columns az_deg,el_deg -o "$W/singer.csv"

# Parse speed against wc -l, both on the turret log in the page cache, best of 3.
best() {
  local b=""
  for _ in 1 2 3; do
    local t0 t1
    t0=$(date +%s.%N); "$@" > "$W/best.out"; t1=$(date +%s.%N)
    b=$(awk -v a="$t0" -v z="$t1" -v b="$b" 'BEGIN { d = z - a; if (b == "" || d < b) print d; else print b }')
  done
  echo "$b"
}
if [ -x "$BENCH" ]; then
  mb=$(awk -v b="$(size "$W/turret.csv")" 'BEGIN { print b / 1e6 }')
  wc_s=$(best wc -l "$W/turret.csv")
  rk_s=$(best env RK_BENCH_CSV="$W/turret.csv" "$BENCH" --benchmark_filter=^BM_CsvReadNumbers$ --benchmark_min_time=0.01 --benchmark_repetitions=1)
  awk -v mb="$mb" -v w="$wc_s" -v r="$rk_s" 'BEGIN { printf "wc -l: %.0f MB/s; CsvTable::Read + every number (bench_csv, whole process): %.0f MB/s = %.2f x wc -l\n", mb / w, mb / r, w / r }'
  env RK_BENCH_CSV="$W/turret.csv" "$BENCH" --benchmark_filter=BM_Csv
fi
