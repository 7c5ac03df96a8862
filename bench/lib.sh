# shellcheck shell=bash
# Sourced by the timing scripts of bench/ (video_read_bench.sh, points_end_to_end.sh); REPEATS must be set.
# median: the median of the numbers on stdin, one per line (the mean of the middle two for an even count).
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
# timed CMD...: wall seconds of CMD (stdout and stderr discarded, its exit status not looked at: a detector
# that finds nothing in random frames still costs its time), median of REPEATS runs.
timed() {
  for _ in $(seq "$REPEATS"); do
    /usr/bin/python3 -c 'import subprocess, sys, time
t = time.perf_counter(); subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print("%.4f" % (time.perf_counter() - t))' "$@"
  done | median
}
