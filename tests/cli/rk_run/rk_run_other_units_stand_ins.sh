#!/usr/bin/env bash
# CLI test rk_run_other_units_stand_ins: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
t=$data/run/standin; b=$data/run/standin_bin; rm -rf "$t" "$b"; mkdir -p "$t/att" "$t/sil" "$t/radar" "$b"
for tool in rk-extract rk-attitude rk-register; do
  cat > "$b/$tool" <<'SH'
#!/usr/bin/env bash
me=$(basename "$0")
if [ "${1:-}" = --version ]; then echo "$me (stand-in) 0"; exit 0; fi
# --help lists the options rk-run checks the manifest's step options against.
if [ "${!#}" = --help ]; then printf 'Options:\n  -o,--output TEXT  out\n  --pd FLOAT  detection probability\n'; exit 0; fi
echo "$me $*" >> "$STANDIN_LOG"
out=""; rep=""; prev=""
for a in "$@"; do
  [ "$prev" = -o ] && out=$a
  [ "$prev" = --report ] && rep=$a
  prev=$a
done
case "$me $1" in
  "rk-register bernoulli"|"rk-register batch") printf 't_s,R1_range_m,R1_az_deg\n0.0,1.5,0.01\n1.0,1.4,0.02\n' > "$out" ;;
  "rk-attitude oi") printf 't_s,e_m,n_m,u_m,yaw_deg,pitch_deg,roll_deg,status\n0.0,1,2,3,10,5,1,ok\n0.1,1,2,3,11,5,1,ok\n' > "$out" ;;
  "rk-attitude cylinder") printf 't_s,yaw_deg,pitch_deg,status\n0.0,10,5,ok\n0.1,11,5,ok\n' > "$out" ;;
  *) printf 'frame,t_s,id,x_px,y_px\n0,0.0,nose,1,2\n' > "$out" ;;
esac
[ -n "$rep" ] && echo '{"tool": "stand-in"}' > "$rep"
exit 0
SH
  chmod +x "$b/$tool"
done
for f in att/000000.png att/000001.png att/frames.csv att/camera.json sil/video.mkv sil/camera.json target.json \
         cylinder.json turret.csv theodolite.csv radar/plots.csv radar/nav.csv; do echo "x" > "$t/$f"; done
cat > "$t/trial.json" <<'JSON'
{"name": "standin", "cameras": {
   "att": {"video": ["att/%06d.png"], "frames": "att/frames.csv", "model": "att/camera.json",
           "role": "features", "target": "target.json"},
   "sil": {"video": "sil/video.mkv", "fps": 25, "model": "sil/camera.json", "role": "silhouette",
           "target": "cylinder.json"}},
 "turret": "turret.csv", "theodolite": "theodolite.csv",
 "radar": {"plots": "radar/plots.csv", "nav": "radar/nav.csv"},
 "steps": {"radar/register": {"pd": 0.9}, "att/plot": false, "sil/plot": false}}
JSON
export STANDIN_LOG=$data/run/standin.log; rm -f "$STANDIN_LOG"
rk-run "$t" --bin "$b" > "$data/run/standin.out"; cat "$data/run/standin.out"; cat "$STANDIN_LOG"
sed -E 's/ --report [^ ]+//; s/out\.tmp\.[A-Za-z0-9]+/out/g' "$STANDIN_LOG" > "$data/run/standin.norm"
cat > "$data/run/standin.expected" <<'EOF2'
rk-extract features --video att/%06d.png --frames att/frames.csv --target target.json -o out/att/points.csv
rk-attitude oi --points out/att/points.csv --camera att/camera.json --target target.json --turret turret.csv -o out/att/pose.csv
rk-extract silhouette --video sil/video.mkv --fps 25 -o out/sil/points.csv
rk-attitude cylinder --points out/sil/points.csv --theodolite theodolite.csv --camera sil/camera.json --target cylinder.json --video sil/video.mkv -o out/sil/axis.csv
rk-register bernoulli --plots radar/plots.csv --nav radar/nav.csv --pd 0.9 -o out/radar/biases.csv
rk-register batch --plots radar/plots.csv --nav radar/nav.csv -o out/radar/biases_batch.csv
EOF2
diff "$data/run/standin.expected" "$data/run/standin.norm"
test ! -e "$t/out/plots/att_pose.png"; grep -Eq '^att/plot-pose +off' "$data/run/standin.out"
for p in radar_biases radar_biases_batch; do test -s "$t/out/plots/$p.png" || { echo "no $p.png"; exit 1; }; done
grep -q -- '--columns R1_range_m,R1_az_deg' "$t/out/steps/radar.plot-biases.log"
check_out --no-temporaries "$t"
rm -f "$STANDIN_LOG"
rk-run "$t" --bin "$b" | grep -q 'up-to-date'
test ! -e "$STANDIN_LOG"
echo "# resurveyed" >> "$t/theodolite.csv"
rk-run "$t" --bin "$b" --no-plots -q
test "$(cut -d' ' -f1,2 "$STANDIN_LOG")" = "rk-attitude cylinder"   # only the step that reads it
echo ok
