#!/usr/bin/env bash
# A sweep through a real Slurm: starts munge, slurmctld and slurmd on this machine as a one-node
# cluster (slurm.conf, keys, state and logs under a temporary folder; nothing system-wide is
# changed), runs the smoke experiment through scripts/sweep_slurm.sh as a job array, runs it again
# locally with `vgi sweep`, and checks that the two results.csv agree in every column but the
# measured times, what is derived from them (the equal-error time ratios: the array's tasks share
# the cores) and the machine. Skips (exit 77) with the reason where Slurm cannot start here:
# not root, or Debian's slurmctld / slurmd / slurm-client / munge not installed
# (apt-get install slurmctld slurmd slurm-client munge).
# Usage: scripts/test_slurm.sh [VGI]   (default build/apps/vgi)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
vgi=$(readlink -f "${1:-build/apps/vgi}")
skip() { echo "test_slurm: SKIPPED: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "not root (slurmd and munged start as root here)"
for b in slurmctld slurmd sbatch squeue sinfo munged; do
  command -v $b > /dev/null || skip "$b not installed (apt-get install slurmctld slurmd slurm-client munge)"
done
t=$(mktemp -d /tmp/vgi-slurm.XXXXXX)
chmod 755 "$t"
host=$(hostname -s)
cleanup() {
  for p in slurmd slurmctld munged; do
    [ -f "$t/$p.pid" ] && kill "$(cat "$t/$p.pid")" 2> /dev/null || true
  done
  sleep 1
  rm -rf "$t"
}
trap cleanup EXIT
mkdir -p "$t/state" "$t/spool" "$t/munge"
chmod 700 "$t/munge"
dd if=/dev/urandom of="$t/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$t/munge/munge.key"
munged --force --key-file="$t/munge/munge.key" --socket="$t/munge/munge.socket" \
  --pid-file="$t/munged.pid" --log-file="$t/munged.log" --seed-file="$t/munge/seed" ||
  skip "munged does not start ($(tail -1 "$t/munged.log" 2> /dev/null))"
cpus=$(nproc)
mem=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)
cat > "$t/slurm.conf" <<CONF
ClusterName=vgitest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$t/munge/munge.socket
StateSaveLocation=$t/state
SlurmdSpoolDir=$t/spool
SlurmctldPidFile=$t/slurmctld.pid
SlurmdPidFile=$t/slurmd.pid
SlurmctldLogFile=$t/slurmctld.log
SlurmdLogFile=$t/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$t/slurm.conf
slurmctld -f "$SLURM_CONF" || skip "slurmctld does not start ($(tail -2 "$t/slurmctld.log" 2> /dev/null))"
slurmd -f "$SLURM_CONF" || skip "slurmd does not start ($(tail -2 "$t/slurmd.log" 2> /dev/null))"
for i in $(seq 60); do
  state=$(sinfo -h -N -o %t 2> /dev/null | head -1)
  [ "$state" = idle ] && break
  sleep 1
done
[ "${state:-}" = idle ] || skip "the node did not come up (sinfo: '${state:-}'; $t/slurmd.log)"
echo "test_slurm: one-node cluster up ($host, $cpus CPUs, $(slurmctld -V))"
experiment=scenes/experiments/smoke.json
VGI=$vgi bash scripts/sweep_slurm.sh "$experiment" "$t/slurm_sweep" --cpus-per-task=1
"$vgi" sweep "$experiment" -o "$t/local" > "$t/local.log" 2>&1
tasks=$(ls "$t/slurm_sweep/slurm" | wc -l)
python3 - "$t/slurm_sweep/results.csv" "$t/local/results.csv" "$tasks" <<'PY'
import csv, sys
measured = {"time_ms", "sample_ms", "setup_ms", "machine", "git_revision"}
def rows(p):
    return sorted([{k: v for k, v in r.items() if k not in measured and "equal_error" not in k}
                   for r in csv.DictReader(open(p))],
                  key=lambda r: sorted(r.items()))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
if a != b or not a:
    print(f"test_slurm: FAIL: results.csv differ ({len(a)} rows through Slurm, {len(b)} locally)")
    for x, y in zip(a, b):
        if x != y: print("  slurm:", x, "\n  local:", y); break
    sys.exit(1)
print(f"test_slurm: PASS: {len(a)} rows from {sys.argv[3]} Slurm array tasks equal the local sweep's "
      "(every column but the measured times, the equal-error time ratios and the machine)")
PY
