#!/usr/bin/env bash
# End-to-end beacon chain on a simulated trial with truth:
#   rk-extract beacon → rk-locate → rk-analyze compare, checked against named tolerances.
#   chain_check.sh TRIAL_DIR WORK_DIR SOURCE_DIR
set -euo pipefail
T=$1; W=$2; SRC=$3
rm -rf "$W"; mkdir -p "$W"
rk-extract beacon --video "$T/az/video.mkv" --frames "$T/az/frames.csv" -o "$W/track.csv" --quiet
rk-locate --track "$W/track.csv" --camera "$T/az/camera.json" --turret "$T/turret.csv" --range "$T/range.csv" \
  -o "$W/located.csv" --quiet
rk-analyze compare --estimate "$W/located.csv" --reference "$T/truth/target.csv" --columns az_deg,el_deg,range_m \
  --arcsec -o "$W/stats.json" --quiet
python3 "$SRC/bench/beacon_track_stats.py" "$W/track.csv" "$T/truth/beacon.csv" > "$W/track_stats.json"
python3 - "$W/stats.json" "$W/track_stats.json" <<'PY'
import json, sys
stats = json.load(open(sys.argv[1]))["columns"]
track = json.load(open(sys.argv[2]))
# Tolerances, each with its reason:
kTrackedFraction = 0.99     # issue target 99.5 % of visible frames; 60-frame trial, one frame is 2 %
kCentroidRmsPx = 0.05       # issue target for a moving scene (peak ~200 DN over ~2 DN noise)
kAngleRmsArcsec = 5.0       # the trial's turret log has the PTU's 0.003 deg (10.8") steps: ~3.1" RMS alone
kRangeRmsM = 0.001          # issue target: 1 mm at frame times with 0.35 mm device noise
kMaxReacquireFrames = 2     # issue target after a 0.5 s occlusion
fails = []
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok: fails.append(what)
check(track["tracked_fraction"] >= kTrackedFraction, "tracked fraction %.4f >= %.3f" % (track["tracked_fraction"], kTrackedFraction))
check(track["false_frames"] == 0, "false frames %d == 0" % track["false_frames"])
for ax in ("x_error_px", "y_error_px"):
    check(track[ax]["rms"] <= kCentroidRmsPx, "%s rms %.4f <= %.3f" % (ax, track[ax]["rms"], kCentroidRmsPx))
check(all(d is not None and d <= kMaxReacquireFrames for d in track["reacquire_delays"]),
      "re-acquisition delays %s <= %d frames" % (track["reacquire_delays"], kMaxReacquireFrames))
for c in ("az_deg", "el_deg"):
    check(stats[c]["unit"] == "arcsec" and stats[c]["rms"] <= kAngleRmsArcsec, "%s rms %.3f\" <= %.1f\"" % (c, stats[c]["rms"], kAngleRmsArcsec))
check(stats["range_m"]["rms"] <= kRangeRmsM, "range rms %.6f m <= %.4f m" % (stats["range_m"]["rms"], kRangeRmsM))
sys.exit(1 if fails else 0)
PY
