# CLI tests of rk-run, rk-nightly and the kill -9 safety target (docs/rk-run.md). Every test copies the
# sim_small trial (rk_sim.cmake: 60 frames of 640x512, range log with a device-error row, truth) into
# its own folder under ${RK_CLI_DATA}/run, because rk-run writes into the trial folder.
# Scripts get $1 = RK_CLI_DATA, $2 = expect.sh, $3 = source dir; tools are found on PATH (RK_BIN first).
set(RK_RUN_CHECK_OUT ${PROJECT_SOURCE_DIR}/tests/run/check_out.py)

function(rk_run_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
    "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; src=$3\ncheck_out() { python3 ${RK_RUN_CHECK_OUT} \"$@\"; }\n"
    "fresh() { rm -rf \"$1\"; mkdir -p \"$(dirname \"$1\")\"; cp -r \"$data/small\" \"$1\"; rm -rf \"$1/out\" \"$1\"/out.* \"$1/rk-run.log\" \"$1/last-run.json\"; }\n"
    "json() { python3 -c \"import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))\" \"$@\"; }\n"
    "${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT}
    ${PROJECT_SOURCE_DIR})
endfunction()

# The beacon chain end to end: every product, report.json (inputs with checksums that sha256sum agrees
# with, tool versions, timings, quality figures), PNG plots, and the located target against truth with
# the tolerances of rk_chain_beacon_small (same tools, same trial: 5" in angle for the turret log's
# 0.003 deg encoder steps, 1 mm in range).
rk_run_script(rk_run_beacon_chain [==[
t=$data/run/chain; fresh "$t"
rk-run "$t" > "$data/run/chain.out"
cat "$data/run/chain.out"
for f in az/track.csv az/located.csv az/smoothed.csv az/range_at_frames.csv plots/az_located.png plots/az_rates.png \
         report.json steps/az.extract-beacon.report.json steps/az.locate.log; do
  test -s "$t/out/$f" || { echo "missing out/$f"; exit 1; }
done
check_out --no-temporaries "$t"
python3 - "$t" "$(sha256sum < "$t/turret.csv" | cut -d' ' -f1)" "$(sha256sum < "$t/az/video.mkv" | cut -d' ' -f1)" <<'PY'
import json, sys
d = json.load(open(sys.argv[1] + "/out/report.json"))
steps = {s["id"]: s for s in d["steps"]}
assert d["result"] == "done", d["result"]
assert sorted(s["status"] for s in d["steps"]) == ["ok"] * 6, [s["status"] for s in d["steps"]]
assert d["inputs"]["turret.csv"]["sha256"] == sys.argv[2] and d["inputs"]["az/video.mkv"]["sha256"] == sys.argv[3]
assert d["tools"]["rk-locate"]["version"].startswith("rk-locate (rangekit) ")
assert steps["az/locate"]["time"]["wall_s"] >= 0 and steps["az/locate"]["tool_report"]["tool"] == "rk-locate"
assert steps["az/extract-beacon"]["quality"]["status"]["ok"] >= 45   # 60 frames, 10 occluded
assert steps["az/locate"]["command_line"][:3] == ["rk-locate", "--track", "out/az/track.csv"]
print("report ok")
PY
head -c 8 "$t/out/plots/az_located.png" | od -c | grep -q 'P   N   G'
grep -q '^t_s,kind,az_deg,el_deg,range_m,e_m,n_m,u_m,status,az_rate_deg_s' "$t/out/az/smoothed.csv"
grep -q ',smoothed,' "$t/out/az/smoothed.csv"
rk-analyze compare --estimate "$t/out/az/located.csv" --reference "$t/truth/target.csv" \
  --columns az_deg,el_deg,range_m --arcsec -o "$data/run/chain_stats.json" -q
python3 - "$data/run/chain_stats.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["columns"]
kAngleRmsArcsec = 5.0   # turret log quantised to 0.003 deg (10.8"): ~3.1" RMS alone
kRangeRmsM = 0.001      # rk-locate's issue target with 0.35 mm device noise
assert c["az_deg"]["rms"] <= kAngleRmsArcsec and c["el_deg"]["rms"] <= kAngleRmsArcsec, c
assert c["range_m"]["rms"] <= kRangeRmsM, c["range_m"]
print("located vs truth ok", c["az_deg"]["rms"], c["el_deg"]["rms"], c["range_m"]["rms"])
PY
test -s "$t/rk-run.log"; test "$(json "$t/last-run.json" 'd["result"]')" = done
echo ok
]==] REQUIRES sim_small)

# Idempotence: unchanged → nothing runs and out/ is the same folder; touch → still up to date (content
# hash); a step option → that step and everything downstream; a changed input → its steps; --force → all.
rk_run_script(rk_run_skip_logic [==[
t=$data/run/skip; fresh "$t"
rk-run "$t" --no-plots -q
ino=$(stat -c %i "$t/out"); rep=$(sha256sum < "$t/out/report.json")
rk-run "$t" --no-plots > "$data/run/skip1.out"; cat "$data/run/skip1.out"
grep -q 'up-to-date (0 run, 4 skipped' "$data/run/skip1.out"
test "$(stat -c %i "$t/out")" = "$ino"; test "$(sha256sum < "$t/out/report.json")" = "$rep"
touch "$t/turret.csv" "$t/az/video.mkv"
rk-run "$t" --no-plots > "$data/run/skip2.out"; grep -q 'up-to-date' "$data/run/skip2.out"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"locate": {"range-interp": "linear"}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots > "$data/run/skip3.out"; cat "$data/run/skip3.out"
grep -Eq '^az/extract-beacon +skipped +up to date' "$data/run/skip3.out"
grep -Eq '^az/locate +ok .*command line or options changed' "$data/run/skip3.out"
grep -Eq '^az/smooth +ok .*upstream changed: az/locate' "$data/run/skip3.out"
grep -Eq '^az/resample-range +skipped' "$data/run/skip3.out"
grep -q -- '--range-interp linear' "$t/out/steps/az.locate.log"
check_out --no-temporaries "$t"
echo "# edited: the content changes, the data do not" >> "$t/range.csv"
rk-run "$t" --no-plots > "$data/run/skip4.out"; cat "$data/run/skip4.out"
grep -Eq '^az/locate +ok .*input changed: range.csv' "$data/run/skip4.out"
grep -Eq '^az/resample-range +ok .*input changed: range.csv' "$data/run/skip4.out"
grep -Eq '^az/extract-beacon +skipped' "$data/run/skip4.out"
rk-run "$t" --no-plots --force > "$data/run/skip5.out"; grep -q 'done (4 run, 0 skipped' "$data/run/skip5.out"
# Switching a step off rebuilds out/ without its product.
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"]["resample-range"] = False
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots -q; test ! -e "$t/out/az/range_at_frames.csv"; test -s "$t/out/az/located.csv"
rk-run "$t" --no-plots --dry-run | grep -Eq '^az/resample-range +off'
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); del j["steps"]["resample-range"]
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
rk-run "$t" --no-plots | grep -Eq '^az/resample-range +ok .*new step \(was off\)'
check_out --no-temporaries "$t"
echo ok
]==] REQUIRES sim_small)

# A failing run leaves the previous good out/ exactly as it was, exits with the step's SPEC code and a
# one-line error naming file:line:col, removes its temporary folder, and records the tool's stderr.
rk_run_script(rk_run_failure_keeps_out [==[
t=$data/run/fail; fresh "$t"
rk-run "$t" --no-plots -q
before=$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)
awk -F, 'NR == 6 { $3 = "abc" } { print }' OFS=, "$t/turret.csv" > "$t/turret.tmp" && mv "$t/turret.tmp" "$t/turret.csv"
"$expect" 3 - "turret.csv:6:[0-9]+: .*step az/locate" -- rk-run "$t" --no-plots
after=$(cd "$t/out" && find . -type f -print0 | sort -z | xargs -0 sha256sum)
test "$before" = "$after" || { echo "out/ changed"; exit 1; }
check_out --no-temporaries "$t"
test "$(json "$t/last-run.json" 'd["result"]')" = failed
test "$(json "$t/last-run.json" 'd["exit_code"]')" = 3
json "$t/last-run.json" '[s for s in d["steps"] if s["id"]=="az/locate"][0]["log_tail"][-1]' | grep -q "rk-locate: error: turret.csv:6:"
grep -q 'FAILED' "$t/rk-run.log"; grep -q '  | rk-locate: error: turret.csv:6:' "$t/rk-run.log"
# --report gets the same summary, also on failure.
"$expect" 3 - -- rk-run "$t" --no-plots --report "$data/run/fail_report.json"
test "$(json "$data/run/fail_report.json" 'd["result"]')" = failed
# Options a tool rejects: exit 3 (the manifest's "steps" are the bad input).
fresh "$t"
python3 - "$t/trial.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["steps"] = {"az/locate": {"no-such-option": 1}}
json.dump(j, open(sys.argv[1], "w"), indent=1)
PY
"$expect" 3 "$t/out" "rejected the options of step az/locate" -- rk-run "$t" --no-plots
check_out --allow-missing --no-temporaries "$t"
echo ok
]==] REQUIRES sim_small)

# The lock: a second run of the same trial exits at once (4) while the first holds it, or waits with
# --wait-lock; stale temporaries and an interrupted two-rename swap are repaired by the next run.
rk_run_script(rk_run_lock_and_recovery [==[
t=$data/run/lock; fresh "$t"
rk-run "$t" --no-plots -q
flock -o "$t/.rk-run.lock" sleep 2 & holder=$!
while flock -n "$t/.rk-run.lock" true; do sleep 0.05; done   # until the holder has it
"$expect" 4 - "locked by another rk-run" -- rk-run "$t" --no-plots
rk-run "$t" --no-plots --wait-lock 60 -q   # waits for the holder, then finds it up to date
wait "$holder"
# Stale temporaries are removed; a swap cut between its two renames is completed from out.old.*.
mkdir -p "$t/out.tmp.AAAAAA/az"; echo partial > "$t/out.tmp.AAAAAA/az/track.csv"
mv "$t/out" "$t/out.old.BBBBBB"
rk-run "$t" --no-plots > "$data/run/lock.out"; cat "$data/run/lock.out"
grep -q 'up-to-date' "$data/run/lock.out"    # the restored out/ is the complete previous one
grep -q 'restored out/ from out.old.BBBBBB' "$t/rk-run.log"
grep -q 'removed stale out.tmp.AAAAAA' "$t/rk-run.log"
check_out --no-temporaries "$t"
echo ok
]==] REQUIRES sim_small)

# Malformed manifests and usage: SPEC codes, one-line errors with trial.json:LINE:COL.
rk_run_script(rk_run_bad_input [==[
d=$data/run/bad; rm -rf "$d"; mkdir -p "$d"
t=$d/syntax; fresh "$t"; printf '{"name": "x",\n "cameras": {\n' > "$t/trial.json"
"$expect" 3 "$t/out" 'trial.json:[0-9]+:[0-9]+: invalid JSON' -- rk-run "$t"
t=$d/role; fresh "$t"; sed -i 's/"role": "beacon"/"role": "beakon"/' "$t/trial.json"
line=$(grep -n beakon "$t/trial.json" | cut -d: -f1)
"$expect" 3 "$t/out" "trial.json:$line:[0-9]+: cameras.az.role: 'beakon' is not one of" -- rk-run "$t"
t=$d/novideo; fresh "$t"
python3 -c "import json,sys; p=sys.argv[1]; m=json.load(open(p)); m['cameras']['az']['video']=[]; json.dump(m,open(p,'w'),indent=1)" "$t/trial.json"
"$expect" 3 "$t/out" 'trial.json:[0-9]+:[0-9]+: cameras.az.video: must be a path or a non-empty list of paths' -- rk-run "$t"
t=$d/step; fresh "$t"; sed -i 's/"steps": {}/"steps": {"locat": {}}/' "$t/trial.json"
"$expect" 3 "$t/out" "trial.json:[0-9]+:[0-9]+: steps.locat: unknown step 'locat'" -- rk-run "$t"
t=$d/reserved; fresh "$t"; sed -i 's/"steps": {}/"steps": {"locate": {"turret": "other.csv"}}/' "$t/trial.json"
"$expect" 3 "$t/out" "steps.locate.turret: option '--turret' is set by rk-run" -- rk-run "$t"
t=$d/missing; fresh "$t"; rm "$t/az/video.mkv"
"$expect" 4 "$t/out" 'az/video.mkv: no such file' -- rk-run "$t"
"$expect" 4 - 'no such trial manifest' -- rk-run "$d/none"
"$expect" 2 - -- rk-run
"$expect" 2 - -- rk-run "$t" --jobs 0
"$expect" 2 - -- rk-run "$t" --bogus
echo ok
]==] REQUIRES sim_small)

# rk-nightly: parallel run over a root of trials, a failing trial reported with its reason, summary JSON
# and text table, log file, non-zero exit; the second run finds everything up to date; a second
# instance exits at once (75).
rk_run_script(rk_nightly_summary [==[
r=$data/run/nightly; rm -rf "$r"; mkdir -p "$r/site"
fresh "$r/t1"; fresh "$r/site/t2"; fresh "$r/site/t3"
awk -F, 'NR == 4 { $2 = "x" } { print }' OFS=, "$r/site/t3/range.csv" > "$r/tmp" && mv "$r/tmp" "$r/site/t3/range.csv"
set +e; rk-nightly "$r" -j 2 --no-plots > "$data/run/nightly1.out" 2>&1; rc=$?; set -e
cat "$data/run/nightly1.out"
test "$rc" = 1
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 2, 'up_to_date': 0, 'skipped_locked': 0, 'failed': 1}"
json "$r/rk-nightly-summary.json" '[t for t in d["trials"] if t["trial"]=="site/t3"][0]["reason"]' | grep -q 'range.csv:4:'
grep -Eq '^site/t3 +failed' "$r/rk-nightly-summary.txt"
grep -q 'summary:' "$r/rk-nightly.log"
check_out --no-temporaries "$r/t1" "$r/site/t2"
check_out --allow-missing --no-temporaries "$r/site/t3"
cp "$data/small/range.csv" "$r/site/t3/range.csv"
rk-nightly "$r" --no-plots -q     # quiet and successful: prints nothing
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]')" = "{'done': 1, 'up_to_date': 2, 'skipped_locked': 0, 'failed': 0}"
flock -o "$r/.rk-nightly/lock" sleep 60 & holder=$!
while flock -n "$r/.rk-nightly/lock" true; do sleep 0.05; done
set +e; timeout 30 rk-nightly "$r" --no-plots 2> "$data/run/nightly2.err"; rc=$?; set -e
kill "$holder"; wait "$holder" 2>/dev/null || true
test "$rc" = 75; grep -q 'another rk-nightly' "$data/run/nightly2.err"   # at once, not after the holder
echo ok
]==] REQUIRES sim_small)

# Target "kill -9 of a nightly run in the middle": the next run finishes every trial, and no trial's out/
# is ever half-written. Three trials that already have a good out/ are all forced to rebuild; rk-nightly is
# killed with SIGKILL while they run (twice, at two moments) (its rk-runs and their tools die with it through PDEATHSIG). Then
# every out/ must be complete (old or new), the next run must bring every trial to done/up-to-date, and
# no temporary may be left.
rk_run_script(rk_nightly_kill9 [==[
r=$data/run/kill; rm -rf "$r"; mkdir -p "$r"
for k in 1 2 3; do fresh "$r/t$k"; done
rk-nightly "$r" --no-plots -q
for delay in 0.5 1.5; do
  rk-nightly "$r" --no-plots --force -q > /dev/null 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid"; wait "$pid" 2>/dev/null || true
  for k in 1 2 3; do flock -w 20 "$r/t$k/.rk-run.lock" true; done   # the killed tree is gone
  check_out "$r"/t*          # complete out/ everywhere (temporaries may remain until the next run)
done
set +e; rk-nightly "$r" --no-plots > "$data/run/kill.out" 2>&1; rc=$?; set -e
cat "$data/run/kill.out"
test "$rc" = 0
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]["failed"]')" = 0
test "$(json "$r/rk-nightly-summary.json" 'd["counts"]["done"] + d["counts"]["up_to_date"]')" = 3
check_out --no-temporaries "$r"/t*
echo ok
]==] REQUIRES sim_small)

# Steps of tools that other issues add (features, silhouette, radar): registered only when the tool and
# its simulator subcommand exist. Each simulates a trial with rk-sim <kind> (which writes trial.json as
# rk-sim beacon does, SPEC.md §6) and checks that rk-run runs that unit's steps to "ok".
function(rk_run_other_unit name tool sim_cmd_file sim_args unit_steps)
  if(TARGET ${tool} AND EXISTS ${PROJECT_SOURCE_DIR}/apps/${sim_cmd_file})
    rk_run_script(${name} "
t=$data/run/${name}; rm -rf \"$t\"
rk-sim ${sim_args} --out \"$t\" --quiet
rk-run \"$t\" --no-plots > \"$data/run/${name}.out\"; cat \"$data/run/${name}.out\"
for s in ${unit_steps}; do
  grep -Eq \"^[^ ]*/$s +ok\" \"$data/run/${name}.out\" || { echo \"step $s did not run ok\"; exit 1; }
done
check_out --no-temporaries \"$t\"
rk-run \"$t\" --no-plots | grep -q up-to-date
echo ok
" ${ARGN})
  endif()
endfunction()
# Small trials: the attitude camera of the sim_attitude_small fixture (1000x800, 40 m), 1 s at 10 fps;
# 0.5 s of 640x640 theodolite frames.
rk_run_other_unit(rk_run_features_oi rk-attitude sim_attitude_cmd.cpp
  "attitude --camera $data/att_cam.json --range-m 40 --duration 1 --fps 10" "extract-features attitude-oi"
  REQUIRES sim_attitude_small)
rk_run_other_unit(rk_run_silhouette_cylinder rk-attitude sim_theodolite_cmd.cpp
  "theodolite --images png --sensor-px 640 --duration 0.5 --speed-mps 50 --track-error-px 10"
  "extract-silhouette attitude-cylinder")
rk_run_other_unit(rk_run_radar_register rk-register sim_radar_cmd.cpp radar "register register-batch")

# Until rk-attitude, rk-register and rk-extract features/silhouette exist, the features, silhouette and radar
# units are exercised with stand-in executables (in a --bin folder, found before the real tools): each
# records its command line and writes a small CSV and report. This checks rk-run's side only — the
# SPEC.md §1.1 command lines it builds, the order, the plots of data-dependent columns, skipping and
# re-running after an input change — not the tools (rk_run_features_oi etc. above do that once they exist).
rk_run_script(rk_run_other_units_stand_ins [==[
t=$data/run/standin; b=$data/run/standin_bin; rm -rf "$t" "$b"; mkdir -p "$t/att" "$t/sil" "$t/radar" "$b"
for tool in rk-extract rk-attitude rk-register; do
  cat > "$b/$tool" <<'SH'
#!/usr/bin/env bash
me=$(basename "$0")
if [ "${1:-}" = --version ]; then echo "$me (stand-in) 0"; exit 0; fi
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
rk-attitude cylinder --points out/sil/points.csv --theodolite theodolite.csv --camera sil/camera.json --target cylinder.json -o out/sil/axis.csv
rk-register bernoulli --plots radar/plots.csv --nav radar/nav.csv -o out/radar/biases.csv --pd 0.9
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
]==])
