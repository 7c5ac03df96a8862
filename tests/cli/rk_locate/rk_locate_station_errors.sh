#!/usr/bin/env bash
# CLI test rk_locate_station_errors: registered, and described, in tests/cli/rk_locate.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
o=$data/locate_station_errors; rm -rf "$o"; mkdir -p "$o"
sim=(rk-sim beacon --preset small --duration 2 --format mkv --seed 3 --quiet)
"${sim[@]}" --out "$o/perfect"
"${sim[@]}" --out "$o/errors" --az-offset-deg 2.5 --tilt-north-deg 0.3 --tilt-east-deg -0.2 --el-axis-tilt-deg 0.1 \
  --time-offset-s 0.02
test -s "$o/errors/truth/pointing.json"
test ! -e "$o/perfect/truth/pointing.json"
grep -q '"time_offset_s": 0.02' "$o/errors/az/camera.json"
locate() {  # trial turret out [more options]
  local t=$1 turret=$2 out=$3; shift 3
  rk-locate --track "$o/$t/truth/beacon.csv" --camera "$o/$t/az/camera.json" --turret "$o/$t/$turret" \
    --range "$o/$t/range.csv" -o "$o/$out.csv" -q "$@"
  rk-analyze compare --estimate "$o/$out.csv" --reference "$o/$t/truth/target.csv" --columns az_deg,el_deg \
    --arcsec -o "$o/$out.json" -q
}
rms() {  # stats column → RMS (arcsec)
  awk -v c="\"$2\"" 'index($0, c ": {") { inside = 1 }
    inside && index($0, "\"rms\":") { v = $0; sub(/.*: /, "", v); sub(/,$/, "", v); print v; exit }' "$1"
}
locate perfect truth/turret.csv perfect_true
locate errors truth/turret.csv errors_true --pointing "$o/errors/truth/pointing.json"
locate perfect turret.csv perfect_logged
locate errors turret.csv errors_logged --pointing "$o/errors/truth/pointing.json"
locate errors turret.csv errors_none
for f in perfect_true errors_true perfect_logged errors_logged errors_none; do
  echo "$f: az $(rms "$o/$f.json" az_deg)″ el $(rms "$o/$f.json" el_deg)″ RMS"
done
# Exact geometry: with the true encoder angles and the true pointing model, only the 1e-4 px rounding of
# truth/beacon.csv remains (< 0.05″), latency included.
for c in az_deg el_deg; do
  awk -v v="$(rms "$o/errors_true.json" $c)" 'BEGIN { exit !(v < 0.05) }'
  # The logged turret: encoder quantisation (0.003°) as for the perfect station, within 5″ RMS.
  awk -v v="$(rms "$o/errors_logged.json" $c)" 'BEGIN { exit !(v < 5) }'
done
# Without the pointing model: degrees off.
awk -v v="$(rms "$o/errors_none.json" az_deg)" 'BEGIN { exit !(v > 3600) }'
echo ok
