#!/bin/sh
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
