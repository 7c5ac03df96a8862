# shellcheck shell=bash disable=SC2154  # data and src are set by the sourcing script
# Sourced by the rk_run/ test scripts (which set data and src).
# check_out ARGS: tests/run/check_out.py (every out/ complete, products re-hashed against report.json).
check_out() { python3 "$src/tests/run/check_out.py" "$@"; }
# fresh DIR: a copy of the sim_small trial without any output of an earlier run.
fresh() { rm -rf "$1"; mkdir -p "$(dirname "$1")"; cp -r "$data/small" "$1"; rm -rf "$1/out" "$1"/out.* "$1/rk-run.log" "$1/last-run.json"; }
# json FILE EXPR: prints EXPR evaluated with d = the JSON of FILE.
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
# other_unit NAME "STEP..." SIM_ARGS...: simulates a trial with rk-sim SIM_ARGS into $data/run/NAME, runs
# rk-run on it, checks that every STEP ran ok and the products are complete, and that a second run
# is up to date.
other_unit() {
  local name=$1 steps=$2 t s
  shift 2
  t=$data/run/$name; rm -rf "$t"
  rk-sim "$@" --out "$t" --quiet
  rk-run "$t" --no-plots > "$data/run/$name.out"; cat "$data/run/$name.out"
  for s in $steps; do
    grep -Eq "^[^ ]*/$s +ok" "$data/run/$name.out" || { echo "step $s did not run ok"; exit 1; }
  done
  check_out --no-temporaries "$t"
  rk-run "$t" --no-plots | grep -q up-to-date
  echo ok
}
# standin_rk_run FILE: writes a stand-in rk-run for rk-nightly --rk-run: it writes a --report saying "done" (one
# step run) and nothing else, so that rk-nightly's own work (summary, index) is tested on trials made by hand;
# for a trial folder named "nopage" the report carries rk-run's warning that the report page was not made; in
# one named "slow" it creates the file "started" and then only sleeps (until it is stopped).
standin_rk_run() {
  cat > "$1" <<'SH'
#!/usr/bin/env bash
m=$1; shift
while [ $# -gt 0 ]; do [ "$1" = --report ] && rep=$2; shift; done
[ "$(basename "$(dirname "$m")")" = slow ] && { touch "$(dirname "$m")/started"; exec sleep 60; }
extra=""
[ "$(basename "$(dirname "$m")")" = nopage ] && extra=', "report_page_warning": "report page not made: stand-in"'
printf '{"tool": "rk-run", "result": "done", "exit_code": 0, "counts": {"run": 1, "skipped": 0}%s}\n' "$extra" > "$rep"
SH
  chmod +x "$1"
}
