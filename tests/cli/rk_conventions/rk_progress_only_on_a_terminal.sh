#!/usr/bin/env bash
# CLI test rk_progress_only_on_a_terminal: registered, and described, in tests/cli/rk_conventions.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
T=$data/small
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
args=(beacon --video "$T/az/video.mkv" --frames "$T/az/frames.csv")
# stderr not a terminal: nothing on it.
rk-extract "${args[@]}" -o "$out/a.csv" 2> "$out/err.txt"
[ ! -s "$out/err.txt" ] || { echo "FAIL: stderr not a terminal but got:"; cat "$out/err.txt"; exit 1; }
# On a pseudo-terminal (script(1) gives the command one): the progress line and the summary.
frames=$(($(grep -vc '^#' "$T/az/frames.csv") - 1))
script -qec "rk-extract ${args[*]} -o $out/b.csv" /dev/null > "$out/tty.txt" < /dev/null
tr '\r' '\n' < "$out/tty.txt" | sed 's/\x1b\[K//g' > "$out/tty_lines.txt"
grep -Eq "^rk-extract: [0-9]+/$frames frames \([0-9]+%\)" "$out/tty_lines.txt" \
  || { echo "FAIL: no progress line with done/total"; cat -v "$out/tty.txt"; exit 1; }
grep -Eq "^rk-extract: $frames frames: [0-9]+ ok" "$out/tty_lines.txt" \
  || { echo "FAIL: no closing summary line"; cat -v "$out/tty.txt"; exit 1; }
cmp "$out/a.csv" "$out/b.csv"
# --quiet: nothing even on a terminal.
script -qec "rk-extract ${args[*]} -o $out/c.csv --quiet" /dev/null > "$out/quiet.txt" < /dev/null
[ ! -s "$out/quiet.txt" ] || { echo "FAIL: --quiet printed:"; cat -v "$out/quiet.txt"; exit 1; }

# rk-register kf and batch, rk-calibrate pointing: the same rules. check_tty NAME PROGRESS SUMMARY CMD...:
# stderr a file -> no progress line; a pseudo-terminal -> a progress line matching PROGRESS and the closing
# summary matching SUMMARY, the same output file; --quiet -> nothing at all.
check_tty() {
  local name=$1 progress=$2 summary=$3; shift 3
  local cmd="$*"
  eval "$cmd -o $out/$name.a" 2> "$out/$name.err"
  if tr '\r' '\n' < "$out/$name.err" | grep -Eq "$progress"; then
    echo "FAIL: $name: progress with stderr not a terminal:"; cat -v "$out/$name.err"; exit 1
  fi
  script -qec "$cmd -o $out/$name.b" /dev/null > "$out/$name.tty" < /dev/null
  tr '\r' '\n' < "$out/$name.tty" | sed 's/\x1b\[K//g' > "$out/$name.lines"
  grep -Eq "$progress" "$out/$name.lines" || { echo "FAIL: $name: no progress line"; cat -v "$out/$name.tty"; exit 1; }
  grep -Eq "$summary" "$out/$name.lines" || { echo "FAIL: $name: no summary line"; cat -v "$out/$name.tty"; exit 1; }
  script -qec "$cmd -o $out/$name.c --quiet" /dev/null > "$out/$name.quiet" < /dev/null
  [ ! -s "$out/$name.quiet" ] || { echo "FAIL: $name: --quiet printed:"; cat -v "$out/$name.quiet"; exit 1; }
}
R=$data/radar3
steps=80   # scans of the sim_radar_data fixture (rk_sim_radar.cmake: scenario 3, 80 scans)
check_tty kf "^rk-register: [0-9]+/$steps steps \([0-9]+%\)" "^rk-register: $steps steps: [0-9]+ updated, [0-9]+ predicted" \
  rk-register kf --plots "$R/plots.csv" --nav "$R/nav.csv"
check_tty batch "^rk-register: [0-9]+/$steps Bernoulli-pass steps \([0-9]+%\)" \
  "^rk-register: $steps steps, [0-9]+ pairs; [0-9]+ rounds, [0-9]+ solver iterations" \
  rk-register batch --plots "$R/plots.csv" --nav "$R/nav.csv"
grep -Eq "^rk-register: [0-9]+/5 association rounds \([0-9]+%\)" "$out/batch.lines" \
  || { echo "FAIL: batch: no progress line of the association rounds"; cat -v "$out/batch.tty"; exit 1; }
S=$data/pointing/session
epoch=$(python3 -c "import json;print(json.load(open('$S/trial.json'))['epoch_utc'])")
station=$(python3 -c "import json;s=json.load(open('$S/trial.json'))['station'];print('%r,%r,%r'%(s['lat_deg'],s['lon_deg'],s['h_m']))")
check_tty pointing "^rk-calibrate: [0-9]+ solves" "^rk-calibrate: [0-9]+ observations: [0-9]+ used, [0-9]+ rejected; RMS" \
  rk-calibrate pointing --observations "$S/points.csv" --turret "$S/turret.csv" --camera "$S/camera.json" \
  --landmarks "$S/landmarks.csv" --stars "$S/stars.csv" --epoch-utc "$epoch" --station "$station" --dut1 0
echo ok
