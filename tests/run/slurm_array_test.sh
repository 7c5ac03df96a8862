#!/usr/bin/env bash
# One-node Slurm from Debian's packages (slurmctld + slurmd + munge), started inside the test with a
# throw-away configuration in a temporary folder: submits `rk-slurm submit ROOT --wait` (the rk-run.sbatch
# job array + the summary job) on three simulated trials, checks every trial's out/ and the summary,
# and tears everything down.
#   slurm_array_test.sh SOURCE_DIR BIN_DIR
# Needs root (slurmd runs jobs as their user) and the packages slurmctld slurmd slurm-client munge
# (scripts/setup.sh --slurm installs them); exits 77 (ctest: skipped) when they are missing.
# Runnable by hand: bash tests/run/slurm_array_test.sh "$PWD" "$PWD/build/apps"
set -euo pipefail
SRC=$1; BIN=$2
for p in /usr/sbin/slurmctld /usr/sbin/slurmd /usr/sbin/munged /usr/bin/sbatch; do
  if [ ! -x "$p" ]; then echo "SKIP: $p missing (scripts/setup.sh --slurm installs Slurm)"; exit 77; fi
done
if [ "$(id -u)" != 0 ]; then echo "SKIP: needs root to run slurmd"; exit 77; fi

T=$(mktemp -d /tmp/rk-slurm-test.XXXXXX)
chmod 755 "$T"
pids=()
cleanup() {
  set +e
  for f in "$T/slurmd.pid" "$T/slurmctld.pid" "$T/munge/munged.pid"; do
    [ -s "$f" ] && kill "$(cat "$f")" 2>/dev/null
  done
  sleep 1
  for f in "$T/slurmd.pid" "$T/slurmctld.pid" "$T/munge/munged.pid"; do
    [ -s "$f" ] && kill -9 "$(cat "$f")" 2>/dev/null
  done
  rm -rf "$T"
}
trap cleanup EXIT

# Free TCP ports on the loopback for slurmctld and slurmd (no clash with a real Slurm or another run).
read -r PCTL PD < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
H=$(hostname -s)
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log" "$T/root"
chmod 700 "$T/munge"
head -c 1024 /dev/urandom > "$T/munge/munge.key"; chmod 600 "$T/munge/munge.key"
/usr/sbin/munged --socket="$T/munge/munge.socket" --key-file="$T/munge/munge.key" \
  --log-file="$T/log/munged.log" --pid-file="$T/munge/munged.pid" --seed-file="$T/munge/munged.seed" --force
cat > "$T/slurm.conf" <<CONF
ClusterName=rktest
SlurmctldHost=$H(127.0.0.1)
SlurmctldPort=$PCTL
SlurmdPort=$PD
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/munge.socket
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
InactiveLimit=0
KillWait=5
NodeName=$H NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=rktest Nodes=$H Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$T/slurm.conf
/usr/sbin/slurmctld -f "$SLURM_CONF" -i
/usr/sbin/slurmd -f "$SLURM_CONF"
for _ in $(seq 1 60); do
  if sinfo -h -o %t 2>/dev/null | grep -q idle; then break; fi
  sleep 0.5
done
sinfo -h -o "%P %t %c" | grep -q idle || { echo "FAIL: the node did not come up"; tail -n 20 "$T"/log/*.log; exit 1; }

# Three small trials (2 s, 40 frames each).
for k in 1 2 3; do
  "$BIN/rk-sim" beacon --out "$T/root/trial$k" --preset small --duration 2 --seed $k --quiet
done
export RK_RUN=$BIN/rk-run
set +e
python3 "$SRC/scripts/rk-slurm" submit "$T/root" --no-plots --wait --time 10 > "$T/submit.out" 2>&1
rc=$?
set -e
cat "$T/submit.out"
if [ "$rc" != 0 ]; then
  echo "FAIL: rk-slurm submit --wait exited $rc"
  for f in "$T"/root/.rk-slurm/*/logs/*.log "$T"/root/.rk-slurm/*/summary.log "$T/log/slurmctld.log"; do
    echo "--- $f"; tail -n 20 "$f"
  done
  exit 1
fi
python3 - "$T/root" <<'PY'
import glob, json, os, sys
root = sys.argv[1]
fails = []
def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok: fails.append(what)
runs = glob.glob(os.path.join(root, ".rk-slurm", "*", "summary.json"))
check(len(runs) == 1, "one summary.json (%d)" % len(runs))
s = json.load(open(runs[0]))
check(s["counts"]["done"] == 3 and s["counts"]["failed"] == 0, "summary counts %s" % s["counts"])
for k in (1, 2, 3):
    out = os.path.join(root, "trial%d" % k, "out")
    rep = json.load(open(os.path.join(out, "report.json")))
    ok_steps = [st["id"] for st in rep["steps"] if st["status"] == "ok"]
    check(rep["result"] == "done" and "az/locate" in ok_steps and "az/smooth" in ok_steps,
          "trial%d report: %s" % (k, ok_steps))
    rows = [l for l in open(os.path.join(out, "az", "located.csv")) if not l.startswith("#")]
    check(len(rows) == 41, "trial%d located.csv has 40 frames (%d rows)" % (k, len(rows) - 1))
    check(not glob.glob(os.path.join(root, "trial%d" % k, "out.tmp.*")), "trial%d no temporaries" % k)
sys.exit(1 if fails else 0)
PY
echo "slurm array test ok"
