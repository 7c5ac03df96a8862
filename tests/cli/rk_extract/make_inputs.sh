#!/bin/sh
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
