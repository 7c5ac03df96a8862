#!/usr/bin/env bash
# CLI test rk_recover_stays_inside: registered, and described, in tests/cli/rk_safety.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
d=$data/safety/recover; rm -rf "$d"; mkdir -p "$d/trial/az"
# A file outside the trial with a "torn" last line: recover must never cut it.
printf 't_s,az_deg,el_deg\n0.0,1,2\n0.1,1,2\n0.2,1' > "$d/victim.csv"
cp "$d/victim.csv" "$d/victim.orig"
manifest() {  # manifest KEY_JSON: a trial left 'recording' whose KEY_JSON names a path
  printf '{\n  "name": "t",\n  "cameras": {},\n  %s,\n  "capture": {"state": "recording"}\n}\n' "$1" > "$d/trial/trial.json"
  cp "$d/trial/trial.json" "$d/trial.orig"
}
unchanged() {
  cmp "$d/victim.csv" "$d/victim.orig" || { echo "FAIL: the file outside the trial was changed"; exit 1; }
  cmp "$d/trial/trial.json" "$d/trial.orig" || { echo "FAIL: trial.json was changed"; exit 1; }
}
for how in check run; do
  opt=(); [ $how = check ] && opt=(--check)
  # ../ in the manifest: exit 3 at the key's line:column, nothing changed.
  manifest '"turret": "../victim.csv"'
  "$expect" 3 - 'trial.json:4:13: turret: .*outside the trial folder' -- rk-capture recover "$d/trial" "${opt[@]}"
  unchanged
  # An absolute path.
  manifest "\"range\": \"$d/victim.csv\""
  "$expect" 3 - 'trial.json:4:12: range: .*outside the trial folder' -- rk-capture recover "$d/trial" "${opt[@]}"
  unchanged
  # A link inside the trial that leads outside.
  ln -sfn ../victim.csv "$d/trial/turret.csv"
  manifest '"turret": "turret.csv"'
  "$expect" 3 - 'trial.json:4:13: turret: .*outside the trial folder' -- rk-capture recover "$d/trial" "${opt[@]}"
  unchanged
  rm "$d/trial/turret.csv"
  # A camera's frames file.
  printf '{\n  "name": "t",\n  "cameras": {"az": {"video": [], "frames": "../victim.csv"}},\n  "capture": {"state": "recording"}\n}\n' \
    > "$d/trial/trial.json"; cp "$d/trial/trial.json" "$d/trial.orig"
  "$expect" 3 - 'trial.json:3:45: cameras.az.frames: .*outside' -- rk-capture recover "$d/trial" "${opt[@]}"
  unchanged
done
# A segment or events.log that is a link to a file outside: not followed, reported, the file untouched.
cp "$d/victim.orig" "$d/victim.csv"
printf '{\n  "name": "t",\n  "cameras": {},\n  "capture": {"state": "recording"}\n}\n' > "$d/trial/trial.json"
ln -sfn ../victim.csv "$d/trial/events.log"
set +e; rk-capture recover "$d/trial" 2> "$d/events.err"; rc=$?; set -e
cat "$d/events.err"
cmp "$d/victim.csv" "$d/victim.orig" || { echo "FAIL: events.log's link target was cut"; exit 1; }
[ $rc = 3 ] || { echo "FAIL: exit $rc, expected 3 (a problem left as found)"; exit 1; }
grep -q 'a link or a path outside the trial folder' "$d/events.err"
echo ok
