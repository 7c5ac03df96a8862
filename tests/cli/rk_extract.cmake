# CLI tests of rk-extract beacon (SPEC.md §1.1, §4): good input (our own
# rendered video and, when rk-sim exists, its `small` trial) and malformed input.
set(RKX $<TARGET_FILE:rk-extract>)
set(RKX_DIR ${RK_CLI_DATA}/extract)
file(MAKE_DIRECTORY ${RKX_DIR})

# Inputs made by ffmpeg: a noise-free 5-lamp cluster (Gaussian lamps, σ 1.2 px,
# background 10 DN) moving at (8, 3) px/s, 160×120, 3 s at 20 fps; its truth is
# the flux-weighted lamp centre (80 + 8t − 0.08, 60 + 3t + 0.484444). Plus a blank
# video, a 16-bit PNG sequence of the same frames, a truncated copy and bad
# frames.csv files.
file(WRITE ${RKX_DIR}/make_inputs.sh [=[#!/bin/sh
set -e
d=$1
mkdir -p "$d/seq"
cd "$d"
L() { echo "$2*exp(-((X-(80+8*T+($1)))^2+(Y-(60+3*T+($3)))^2)/2.88)"; }
EXPR="10+$(L 0 100 0)+$(L 3.2 85 0.4)+$(L -2.6 90 1.9)+$(L 0.5 80 -3.4)+$(L -1.2 95 3.0)"
ffmpeg -v error -nostdin -y -f lavfi -i "nullsrc=s=160x120:r=20,format=gray,geq=lum='$EXPR'" -t 3 -pix_fmt gray -c:v ffv1 beacon.mkv
ffmpeg -v error -nostdin -y -f lavfi -i "nullsrc=s=160x120:r=20,format=gray,geq=lum=10" -t 1 -pix_fmt gray -c:v ffv1 blank.mkv
ffmpeg -v error -nostdin -y -i beacon.mkv -pix_fmt gray16be seq/%06d.png
head -c 6000 beacon.mkv > truncated.mkv
awk 'BEGIN{print "frame,t_s"; for(i=0;i<60;i++) printf "%d,%.6f\n", i, 100+i/20}' > frames.csv
awk 'BEGIN{print "frame,t_s"; for(i=0;i<50;i++) printf "%d,%.6f\n", i, i/20}' > frames_short.csv
awk 'BEGIN{print "frame,t_s"; for(i=0;i<70;i++) printf "%d,%.6f\n", i, i/20}' > frames_long.csv
printf 'frame,t_s\n0,0.0\n1,0.05\n2,abc\n' > frames_text.csv
printf 'frame,t_s\n0,0.0\n1,0.05\n2,0.04\n' > frames_back.csv
]=])
# Checks a track against the analytic truth: row count, all ok, RMS error.
file(WRITE ${RKX_DIR}/check_track.sh [=[#!/bin/sh
# check_track.sh TRACK ROWS T0 MAXRMS
awk -F, -v rows="$2" -v t0="$3" -v maxrms="$4" '
  NR==1 { for (i=1;i<=NF;i++) c[$i]=i; next }
  /^#/ { next }
  { t=$c["t_s"]-t0; ex=$c["x_px"]-(80+8*t-0.08); ey=$c["y_px"]-(60+3*t+0.484444); s+=ex*ex+ey*ey; n++
    if ($c["status"]!="ok") bad++ }
  END { rms=sqrt(s/(2*n)); printf "rows %d, not ok %d, rms %.4f px\n", n, bad, rms
        if (n!=rows || bad>0 || rms>maxrms) exit 1 }' "$1"
]=])

rk_cli_test(extract_cli_inputs SETUP extract_inputs COMMAND sh ${RKX_DIR}/make_inputs.sh ${RKX_DIR})

# Good input: frames.csv (t from 100 s), report, analytic truth (8-bit quantisation
# of noise-free lamps leaves < 0.02 px).
rk_cli_test(extract_cli_beacon_good REQUIRES extract_inputs COMMAND sh -c
  "rm -f ${RKX_DIR}/track.csv ${RKX_DIR}/report.json && ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames.csv -o ${RKX_DIR}/track.csv --report ${RKX_DIR}/report.json --quiet && sh ${RKX_DIR}/check_track.sh ${RKX_DIR}/track.csv 60 100 0.02 && grep -q '\"ok\": 60' ${RKX_DIR}/report.json && grep -q '\"mean_ncc\"' ${RKX_DIR}/report.json")
# --fps, 16-bit PNG sequence, two segments (frame counts on).
rk_cli_test(extract_cli_beacon_seq16_fps REQUIRES extract_inputs COMMAND sh -c
  "${RKX} beacon --video '${RKX_DIR}/seq/%06d.png' --fps 20 --t0 0 -o ${RKX_DIR}/track16.csv && sh ${RKX_DIR}/check_track.sh ${RKX_DIR}/track16.csv 60 0 0.02")
rk_cli_test(extract_cli_beacon_segments REQUIRES extract_inputs COMMAND sh -c
  "${RKX} beacon --video ${RKX_DIR}/beacon.mkv --video ${RKX_DIR}/beacon.mkv --fps 20 -o - | awk -F, 'NR>1{n++} END{exit n!=120}'")
# -o - writes the CSV to stdout.
rk_cli_test(extract_cli_beacon_stdout REQUIRES extract_inputs COMMAND sh -c
  "${RKX} beacon --video ${RKX_DIR}/beacon.mkv --fps 20 -o - | head -n 1 | grep -qx 'frame,t_s,x_px,y_px,peak,area_px,status,ncc,sigma_x_px,sigma_y_px'")
rk_cli_test(extract_cli_decode_only REQUIRES extract_inputs COMMAND sh -c
  "${RKX} beacon --video ${RKX_DIR}/beacon.mkv --decode-only 2>&1 >/dev/null | grep -q 'decoded 60 frames'")

# Malformed input / usage (exit codes of SPEC.md §4, no partial output).
rk_cli_test(extract_cli_no_times REQUIRES extract_inputs COMMAND ${RK_EXPECT} 2 ${RKX_DIR}/bad.csv "--frames" --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_unknown_option REQUIRES extract_inputs COMMAND ${RK_EXPECT} 2 ${RKX_DIR}/bad.csv --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --fps 20 --bogus 3 -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_no_subcommand COMMAND ${RK_EXPECT} 2 - -- ${RKX})
rk_cli_test(extract_cli_missing_video COMMAND ${RK_EXPECT} 4 ${RKX_DIR}/bad.csv "nope.mkv" --
  ${RKX} beacon --video ${RKX_DIR}/nope.mkv --fps 20 -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_truncated_video REQUIRES extract_inputs COMMAND ${RK_EXPECT} 3 ${RKX_DIR}/bad.csv "truncated.mkv" --
  ${RKX} beacon --video ${RKX_DIR}/truncated.mkv --fps 20 -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_frames_text REQUIRES extract_inputs COMMAND ${RK_EXPECT} 3 ${RKX_DIR}/bad.csv "frames_text.csv:4:3" --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames_text.csv -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_frames_backwards REQUIRES extract_inputs COMMAND ${RK_EXPECT} 3 ${RKX_DIR}/bad.csv "frames_back.csv:4" --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames_back.csv -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_frames_too_few REQUIRES extract_inputs COMMAND ${RK_EXPECT} 3 ${RKX_DIR}/bad.csv "frames_short.csv" --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames_short.csv -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_frames_too_many REQUIRES extract_inputs COMMAND ${RK_EXPECT} 3 ${RKX_DIR}/bad.csv "beacon.mkv.*truncated" --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames_long.csv -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_nothing_detected REQUIRES extract_inputs COMMAND ${RK_EXPECT} 1 ${RKX_DIR}/bad.csv "nothing detected" --
  ${RKX} beacon --video ${RKX_DIR}/blank.mkv --fps 20 -o ${RKX_DIR}/bad.csv)
rk_cli_test(extract_cli_output_is_input REQUIRES extract_inputs COMMAND ${RK_EXPECT} 2 - --
  ${RKX} beacon --video ${RKX_DIR}/beacon.mkv --frames ${RKX_DIR}/frames.csv -o ${RKX_DIR}/frames.csv)

# End to end on rk-sim's small trial (fixture sim_small), when rk-sim is built:
# one row per truth frame, visible frames ok (≥ 99 %) within 0.25 px of truth,
# and no position on a frame where the beacon is not visible.
if(TARGET rk-sim)
  file(WRITE ${RKX_DIR}/check_sim.sh [=[#!/bin/sh
# check_sim.sh TRACK TRUTH
awk -F, '
  FNR==1 { f++; for (i=1;i<=NF;i++) c[f,$i]=i; next }
  /^#/ { next }
  f==1 { k=$c[1,"frame"]; st[k]=$c[1,"status"]; x[k]=$c[1,"x_px"]; y[k]=$c[1,"y_px"]; rows++; next }
  f==2 { k=$c[2,"frame"]; n++
         if (!(k in st)) { print "no row for frame " k; bad=1; next }
         if ($c[2,"visible"]+0 == 1) { vis++
           if (st[k]=="ok" || st[k]=="reacquired") { ok++
             e=sqrt((x[k]-$c[2,"x_px"])^2 + (y[k]-$c[2,"y_px"])^2); if (e>emax) emax=e } }
         else if (x[k]!="") { print "position on hidden frame " k; bad=1 } }
  END { printf "rows %d truth %d visible %d ok %d max err %.4f px\n", rows, n, vis, ok, emax
        if (bad || rows!=n || ok < 0.99*vis || emax > 0.25) exit 1 }' "$1" "$2"
]=])
  rk_cli_test(extract_cli_sim_small REQUIRES sim_small COMMAND sh -c
    "${RKX} beacon --video ${RK_CLI_DATA}/small/az/video.mkv --frames ${RK_CLI_DATA}/small/az/frames.csv -o ${RKX_DIR}/sim_track.csv --quiet && sh ${RKX_DIR}/check_sim.sh ${RKX_DIR}/sim_track.csv ${RK_CLI_DATA}/small/truth/beacon.csv")

  # Issue 15 item 2: the image motion turns during a short occlusion (rk-sim --servo-hold: the turret
  # stops for 0.4 s, then catches up; the beacon is hidden from 0.2 s into the hold for 0.5 s), with and
  # without glints in view. Frames after the return must be measured within 2 frames and stay measured;
  # no position on a hidden frame; every position within 0.5 px of truth.
  file(WRITE ${RKX_DIR}/check_return.sh [=[#!/bin/sh
# check_return.sh TRACK TRUTH
awk -F, '
  FNR==1 { f++; for (i=1;i<=NF;i++) c[f,$i]=i; next }
  /^#/ { next }
  f==1 { k=$c[1,"frame"]; st[k]=$c[1,"status"]; x[k]=$c[1,"x_px"]; y[k]=$c[1,"y_px"]; next }
  f==2 { k=$c[2,"frame"]; vis=$c[2,"visible"]+0; meas=(st[k]=="ok" || st[k]=="reacquired")
         if (!vis) { hidden=1; if (x[k]!="") { print "position on hidden frame " k; bad=1 }; next }
         if (hidden) { hidden=0; back=k; waiting=1; returns++ }
         if (meas) { e=sqrt((x[k]-$c[2,"x_px"])^2 + (y[k]-$c[2,"y_px"])^2); if (e>emax) emax=e
                     if (waiting) { d=k-back; if (d>dmax) dmax=d; waiting=0 } }
         else if (!waiting && returns) { print "frame " k " not measured after the re-acquisition"; bad=1 }
         else if (waiting && k-back>=2) { print "frame " k ": still " st[k] " " k-back " frames after the return"; bad=1 } }
  END { printf "returns %d, worst re-acquisition %d frames after the return, max err %.4f px\n", returns, dmax, emax
        if (bad || returns<1 || waiting || emax>0.5) exit 1 }' "$1" "$2"
]=])
  foreach(glints 0 3)
    rk_cli_test(extract_cli_sim_reversal_g${glints} COMMAND sh -c
      "d=${RKX_DIR}/reversal_g${glints} && ${RK_BIN}/rk-sim beacon --out $d --force --preset small --duration 4 --seed 5 --servo-hold 1.5:0.4 --occlusion 1.7:0.5 --distractors ${glints} --quiet && ${RKX} beacon --video $d/az/video.mkv --frames $d/az/frames.csv -o $d/track.csv --quiet && sh ${RKX_DIR}/check_return.sh $d/track.csv $d/truth/beacon.csv")
  endforeach()

  # Issue 15 item 6: a sparse cluster (0.1 m: five separate spots at 80 m) is measured by the per-lamp
  # estimator, which the report names; positions within 0.25 px of truth.
  rk_cli_test(extract_cli_sim_sparse_per_lamp COMMAND sh -c
    "d=${RKX_DIR}/sparse && ${RK_BIN}/rk-sim beacon --out $d --force --preset small --duration 2 --seed 6 --cluster-span-m 0.1 --quiet && ${RKX} beacon --video $d/az/video.mkv --frames $d/az/frames.csv -o $d/track.csv --report $d/report.json --quiet && sh ${RKX_DIR}/check_sim.sh $d/track.csv $d/truth/beacon.csv && grep -q '\"per_lamp\": 40' $d/report.json && grep -q '\"cluster\": 0' $d/report.json")
endif()
