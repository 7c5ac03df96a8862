#!/usr/bin/env bash
# Seed 000 Table 1 reproduction and NEES Monte Carlo for `rk-smooth aukf` (issue 3).
#   bench/aukf_table1.sh [OUT]            needs a Release build with rk-sim and rk-smooth
# Writes everything under OUT (default /tmp/rk-aukf-bench) and prints a Markdown summary
# (also OUT/summary.md) for docs/benchmarks.md.
#
# Part 1 (Table 1): SEEDS runs of `rk-sim posetrack --scenario turntable` (seed 000's
#   experiment: yaw at 10°/s, 20 fps, 0–9 s, angle noise 0.0724°), each filtered by
#   `rk-smooth aukf --columns x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg --smooth`. Errors of
#   the COLUMN (yaw_deg) after convergence, t − t0 ≥ AFTER s (default 1 s: the paper only
#   says "after the filter reached steady state"; its Fig. 3 settles within a few frames),
#   against truth at sample times (measurement, estimate, smoothed) and at mid-times
#   (prediction, smoothed). Targets: prediction std ≤ 1.02 × measurement std; smoothed std
#   ≤ 0.6 × measurement std at sample and mid-times.
# Part 2 (NEES): MC runs of `rk-sim posetrack --scenario head` (maneuvering 6-DOF, 20 s),
#   `rk-smooth aukf --sigmas`; NEES of the estimate (or NEES_KIND) from the per-column sigmas (expected 6),
#   fraction of runs inside the 95 % chi-square band, divergence = |error| > 10 sigma.
#   Skipped (with a note) when rk-smooth aukf has no --sigmas option.
# A run on which rk-smooth fails (non-zero exit) is not analysed but counted: in the tables
# as "rk-smooth failed" (for NEES it counts as a divergence); its stderr is kept in the run
# folder (aukf_stderr.txt).
# Environment: BIN (default <repo>/build/apps), SEEDS (20), MC (100), AFTER (1.0),
#   COLUMN (yaw_deg), AUKF_OPTS (extra rk-smooth aukf options, default none), NEES_KIND (estimate or
#   prediction: the rows whose NEES part 2 reports),
#   PYTHON (python3; the analysis uses the standard library only).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${BIN:-$ROOT/build/apps}
OUT=${1:-/tmp/rk-aukf-bench}
SEEDS=${SEEDS:-20}
MC=${MC:-100}
AFTER=${AFTER:-1.0}
COLUMN=${COLUMN:-yaw_deg}
AUKF_OPTS=${AUKF_OPTS:-}
NEES_KIND=${NEES_KIND:-estimate}
PYTHON=${PYTHON:-python3}
PY="$PYTHON $ROOT/bench/aukf_table1.py"
COLS=x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg
for tool in rk-sim rk-smooth; do
  [ -x "$BIN/$tool" ] || { echo "aukf_table1.sh: error: $BIN/$tool not built (set BIN)" >&2; exit 1; }
done
"$BIN/rk-smooth" aukf --help >/dev/null 2>&1 || { echo "aukf_table1.sh: error: rk-smooth has no aukf subcommand" >&2; exit 1; }
mkdir -p "$OUT"
S=$OUT/summary.md
: > "$S"
say() { echo "$*" | tee -a "$S"; }

say "## rk-smooth aukf — seed 000 Table 1 (issue 3) — $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores"
say ""
say "Turntable scenario (\`rk-sim posetrack --scenario turntable\`: yaw 10°/s, 20 fps, 0–9 s, angle noise"
say "std 0.0724°, position noise 0.5 mm), \`rk-smooth aukf --columns $COLS --smooth${AUKF_OPTS:+ $AUKF_OPTS}\`;"
say "errors of \`$COLUMN\` (value − truth, degrees) for t − t0 ≥ $AFTER s; $SEEDS seeds (1…$SEEDS)."
say ""
runs=(); failed=()
for s in $(seq 1 "$SEEDS"); do
  d=$OUT/turntable/seed_$s
  "$BIN/rk-sim" posetrack --out "$d" --force --scenario turntable --seed "$s" --quiet
  # shellcheck disable=SC2086
  if "$BIN/rk-smooth" aukf -i "$d/measurements.csv" --columns "$COLS" --smooth $AUKF_OPTS \
       -o "$d/out.csv" --report "$d/aukf_report.json" --quiet 2>"$d/aukf_stderr.txt"; then
    runs+=("$d")
  else
    failed+=("$d"); echo "rk-smooth failed on $d: $(head -n 1 "$d/aukf_stderr.txt")" >&2
  fi
done
[ ${#runs[@]} -gt 0 ] || { say "rk-smooth aukf failed on every turntable run"; exit 1; }
$PY table1 --column "$COLUMN" --after "$AFTER" --failed ${#failed[@]} --json "$OUT/table1.json" "${runs[@]}" | tee -a "$S"

say "### NEES on the maneuvering head profile"
say ""
if "$BIN/rk-smooth" aukf --help 2>&1 | grep -q -- '--sigmas'; then
  say "\`rk-sim posetrack --scenario head\` (6 DOF, 20 s at 20 fps, sums of sines 0.1–2 Hz, yaw crossing north),"
  say "seeds 1001…$((1000 + MC)), \`rk-smooth aukf --columns $COLS --sigmas${AUKF_OPTS:+ $AUKF_OPTS}\`."
  say ""
  runs=(); failed=()
  for r in $(seq 1 "$MC"); do
    d=$OUT/head/run_$r
    "$BIN/rk-sim" posetrack --out "$d" --force --scenario head --seed $((1000 + r)) --quiet
    # shellcheck disable=SC2086
    if "$BIN/rk-smooth" aukf -i "$d/measurements.csv" --columns "$COLS" --sigmas $AUKF_OPTS \
         -o "$d/out.csv" --report "$d/aukf_report.json" --quiet 2>"$d/aukf_stderr.txt"; then
      runs+=("$d")
    else
      failed+=("$d"); echo "rk-smooth failed on $d: $(head -n 1 "$d/aukf_stderr.txt")" >&2
    fi
  done
  if [ ${#runs[@]} -gt 0 ]; then
    $PY nees --columns "$COLS" --after "$AFTER" --kind "$NEES_KIND" --failed ${#failed[@]} --json "$OUT/nees.json" \
      "${runs[@]}" | tee -a "$S"
  else
    say "rk-smooth aukf failed on every head run"
  fi
else
  say "(skipped: this rk-smooth aukf has no --sigmas option, so the filter's covariance is not in its output)"
  say ""
fi
echo "summary: $S" >&2
