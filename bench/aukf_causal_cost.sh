#!/usr/bin/env bash
# Cost of the causal noise fit of `rk-smooth aukf` against the whole-file fit (the old default), on the
# seed 000 Table 1 turntable and the manoeuvring head profile (issue 3 benchmarks).
#   bench/aukf_causal_cost.sh [OUT]        needs a Release build with rk-sim and rk-smooth
# For each configuration below, SEEDS turntable runs (seeds 1…SEEDS) and MC head runs (seeds 1001…1000+MC) of
# `rk-sim posetrack`, each through `rk-smooth aukf --columns x_m,...,roll_deg --smooth --sigmas <options>`;
# prints the mean over the runs of std(error)/std(measurement error) for t ≥ AFTER s (prediction at mid-times,
# estimate, smoothed at sample and mid-times: aukf_table1.py table1) for the turntable yaw and the head yaw and
# x, and the head NEES of the 6 outputs at prediction and estimate rows (aukf_table1.py nees).
# Environment: BIN (default <repo>/build/apps), SEEDS (20), MC (100), AFTER (1.0), PYTHON (python3).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${BIN:-$ROOT/build/apps}
OUT=${1:-/tmp/rk-aukf-causal}
SEEDS=${SEEDS:-20}
MC=${MC:-100}
AFTER=${AFTER:-1.0}
PYTHON=${PYTHON:-python3}
PY="$PYTHON $ROOT/bench/aukf_table1.py"
COLS=x_m,y_m,z_m,yaw_deg,pitch_deg,roll_deg
CONFIGS=("default|" "old default: --noise-fit file|--noise-fit file" "--smooth-noise-fit causal|--smooth-noise-fit causal")
for tool in rk-sim rk-smooth; do
  [ -x "$BIN/$tool" ] || { echo "aukf_causal_cost.sh: error: $BIN/$tool not built (set BIN)" >&2; exit 1; }
done
mkdir -p "$OUT"
for s in $(seq 1 "$SEEDS"); do
  "$BIN/rk-sim" posetrack --out "$OUT/sim/turntable_$s" --force --scenario turntable --seed "$s" --quiet
done
for r in $(seq 1 "$MC"); do
  "$BIN/rk-sim" posetrack --out "$OUT/sim/head_$r" --force --scenario head --seed $((1000 + r)) --quiet
done
echo "| configuration | turntable yaw: prediction / estimate / smoothed@sample / smoothed@mid | head yaw: same | head x: same | head NEES (6 outputs, expected 6): prediction / estimate |"
echo "|---|---|---|---|---|"
i=0
for cfg in "${CONFIGS[@]}"; do
  label=${cfg%%|*}; opts=${cfg#*|}; i=$((i + 1))
  for scen in turntable head; do
    n=$SEEDS; [ "$scen" = head ] && n=$MC
    runs=()
    for r in $(seq 1 "$n"); do
      d=$OUT/c$i/${scen}_$r; mkdir -p "$d"
      cp "$OUT/sim/${scen}_$r/measurements.csv" "$OUT/sim/${scen}_$r/truth.csv" "$d/"
      # shellcheck disable=SC2086
      "$BIN/rk-smooth" aukf -i "$d/measurements.csv" --columns "$COLS" --smooth --sigmas $opts -o "$d/out.csv" --quiet
      runs+=("$d")
    done
    if [ "$scen" = turntable ]; then
      $PY table1 --column yaw_deg --after "$AFTER" --json "$OUT/c$i/turntable_yaw.json" "${runs[@]}" > /dev/null
    else
      $PY table1 --column yaw_deg --after "$AFTER" --json "$OUT/c$i/head_yaw.json" "${runs[@]}" > /dev/null
      $PY table1 --column x_m --after "$AFTER" --json "$OUT/c$i/head_x.json" "${runs[@]}" > /dev/null
      for kind in prediction estimate; do
        $PY nees --columns "$COLS" --after "$AFTER" --kind $kind --json "$OUT/c$i/nees_$kind.json" "${runs[@]}" > /dev/null
      done
    fi
  done
  $PYTHON - "$OUT/c$i" "$label" <<'PYEOF'
import json, sys
d, label = sys.argv[1], sys.argv[2]
def ratios(name):
    m = json.load(open(f"{d}/{name}.json"))["mean"]
    est = m["estimate"]["std"] / m["measurement"]["std"]
    return "%.3f / %.3f / %.3f / %.3f" % (m["ratio_prediction"], est, m["ratio_smoothed_sample"], m["ratio_smoothed_mid"])
def nees(kind):
    j = json.load(open(f"{d}/nees_{kind}.json"))
    return "%.2f (%.0f %% of times in band, %d runs > 10σ)" % (
        j["grand_mean_nees"], 100.0 * j["anees_in_band"] / max(1, j["anees_steps"]), j["diverged_runs"])
print("| %s | %s | %s | %s | %s / %s |" % (label, ratios("turntable_yaw"), ratios("head_yaw"), ratios("head_x"),
                                          nees("prediction"), nees("estimate")))
PYEOF
done
