#!/bin/sh
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
