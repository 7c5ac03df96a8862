#!/bin/sh
# check_track.sh TRACK ROWS T0 MAXRMS
awk -F, -v rows="$2" -v t0="$3" -v maxrms="$4" '
  NR==1 { for (i=1;i<=NF;i++) c[$i]=i; next }
  /^#/ { next }
  { t=$c["t_s"]-t0; ex=$c["x_px"]-(80+8*t-0.08); ey=$c["y_px"]-(60+3*t+0.484444); s+=ex*ex+ey*ey; n++
    if ($c["status"]!="ok") bad++ }
  END { rms=sqrt(s/(2*n)); printf "rows %d, not ok %d, rms %.4f px\n", n, bad, rms
        if (n!=rows || bad>0 || rms>maxrms) exit 1 }' "$1"
