#!/usr/bin/env bash
# CLI test rk_analyze_good: registered, and described, in tests/cli/rk_analyze.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/analyze; o=$d/out; rm -rf "$o"; mkdir -p "$o"
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg,range_m \
  -o "$o/stats.json" --errors "$o/errors.csv" --table > "$o/table.txt"
for k in '"tool": "rk-analyze"' '"command_line"' '"inputs"' '"columns"' '"p95_abs"' '"unit": "deg"' '"unit": "m"' \
         '"estimate_empty": 1' '"reference_outside": 1'; do
  grep -q "$k" "$o/stats.json" || { echo "missing $k"; exit 1; }
done
# mean az error = (−0.01 + 0.05)/2 = 0.02; range errors 0.5, −0.1 → max 0.5, min −0.1
python3 - "$o/stats.json" <<'EOF'
import json, math, sys
c = json.load(open(sys.argv[1]))["columns"]
near = lambda a, b: abs(a - b) < 1e-9
a, r = c["az_deg"], c["range_m"]
assert a["n"] == 2 and near(a["max"], 0.05) and near(a["min"], -0.01) and near(a["mean"], 0.02), a
assert near(a["std"], math.sqrt(2 * 0.03 ** 2)) and near(a["rms"], math.sqrt((0.01 ** 2 + 0.05 ** 2) / 2)), a
assert near(a["p95_abs"], 0.01 + 0.95 * 0.04), a
assert r["n"] == 2 and near(r["max"], 0.5) and near(r["min"], -0.1) and near(r["mean"], 0.2), r
assert r["n_skipped"] == {"estimate_empty": 0, "reference_outside": 1, "reference_gap": 0, "time_window": 0}, r
EOF
head -1 "$o/errors.csv" | grep -qx 't_s,err_az_deg,err_range_m'
test "$(grep -c '' "$o/errors.csv")" = 4
grep -q '^2.500000000,,$' "$o/errors.csv"
grep -q '^az_deg .* 2 ' "$o/table.txt"
# --arcsec, --after/--before, stdout, table on stderr with -o -
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg --arcsec --after 1 -o - \
  --table 2> "$o/table_err.txt" > "$o/arcsec.json"
python3 - "$o/arcsec.json" <<'EOF'
import json, sys
a = json.load(open(sys.argv[1]))["columns"]["az_deg"]
assert a["unit"] == "arcsec" and a["n"] == 1 and abs(a["max"] - 180.0) < 1e-6 and a["std"] is None, a
assert a["n_skipped"]["time_window"] == 1, a
EOF
grep -q '^az_deg  *arcsec' "$o/table_err.txt"
# nothing comparable: null statistics and a warning, exit 0
rk-analyze compare --estimate "$d/est.csv" --reference "$d/ref.csv" --columns az_deg --before 0.1 -o "$o/none.json" \
  2> "$o/warn.txt"
grep -q '^rk-analyze: warning: column az_deg' "$o/warn.txt"
python3 -c 'import json, sys; a = json.load(open(sys.argv[1]))["columns"]["az_deg"]; assert a["n"] == 0 and all(a[k] is None for k in ("max", "min", "mean", "std", "rms", "p95_abs")), a' "$o/none.json"
echo ok
