#!/usr/bin/env bash
# The Slurm example for real: a single-node Slurm (Debian's slurm-wlm and munge) on this machine,
# in a private folder with its own ports and munge socket, runs examples/slurm/submit.sh on a
# journal in N shards; the merged CSVs must equal the unsharded run's byte for byte.
# usage: slurm_local.sh FAULTLINE JOURNAL DATA OUTDIR [N]
# Needs root (slurmd launches jobs) and the packages (scripts/setup.sh installs them); exits 77
# (CTest: skipped) without them, unless FAULTLINE_REQUIRE_SLURM=1.
set -euo pipefail
faultline=$(realpath "$1") journal=$(realpath "$2") data=$(realpath "$3") out=$(realpath -m "$4")
n=${5:-2}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

skip() {
    echo "slurm test skipped: $*" >&2
    [ "${FAULTLINE_REQUIRE_SLURM:-0}" = 1 ] && exit 1
    exit 77
}
[ "$(id -u)" -eq 0 ] || skip "needs root to run slurmd"
for tool in slurmctld slurmd munged sbatch sinfo squeue; do
    command -v "$tool" >/dev/null || PATH=$PATH:/usr/sbin
    command -v "$tool" >/dev/null || skip "$tool is not installed (apt-get install slurm-wlm munge)"
done
[ -r /etc/munge/munge.key ] || skip "no /etc/munge/munge.key (the munge package makes it)"

rm -rf "$out"
mkdir -p "$out"/{state,spool,munge,results}
chmod 755 "$out/munge"
host=$(hostname -s)
cpus=$(nproc)
# Ports of our own so that a real Slurm on this machine is not disturbed.
port=$((17000 + RANDOM % 2000))
cat >"$out/slurm.conf" <<CONF
ClusterName=faultline-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$out/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$out/state
SlurmdSpoolDir=$out/spool
SlurmctldPidFile=$out/slurmctld.pid
SlurmdPidFile=$out/slurmd.pid
SlurmctldLogFile=$out/slurmctld.log
SlurmdLogFile=$out/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
# Schedule at once (the defaults wait up to a minute for the merge job after its dependency).
SchedulerParameters=sched_interval=1,bf_interval=1
MpiDefault=none
ReturnToService=2
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$out/slurm.conf
pids=()
cleanup() {
    scancel --quiet --user=root >/dev/null 2>&1 || true
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    wait 2>/dev/null || true
}
trap cleanup EXIT
munged --foreground --socket="$out/munge/munge.socket" --pid-file="$out/munge/munged.pid" \
    --log-file="$out/munge/munged.log" --seed-file="$out/munge/munged.seed" --force \
    >"$out/munge/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$out/munge/munge.socket" ] && break; sleep 0.1; done
slurmctld -D -f "$out/slurm.conf" >"$out/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$out/slurm.conf" >"$out/slurmd.out" 2>&1 &
pids+=($!)
ready=0
for _ in $(seq 60); do
    if sinfo -h -o '%t' 2>/dev/null | grep -qE '^idle'; then ready=1; break; fi
    sleep 0.5
done
if [ "$ready" -ne 1 ]; then
    echo "FAIL: the local Slurm did not come up; its logs:" >&2
    tail -20 "$out"/slurmctld.log "$out"/slurmd.log "$out"/slurmd.out "$out"/slurmctld.out >&2 || true
    exit 1
fi

# The unsharded run, then the example on Slurm.
start=$(date +%s.%N)
"$faultline" replay "$journal" --data "$data" --out "$out/whole" >/dev/null
whole=$(echo "$(date +%s.%N) - $start" | bc)
start=$(date +%s.%N)
# Submitted without --wait: sbatch --wait polls at growing intervals (tens of seconds); the
# merge job's state is polled here every half second instead.
if ! FAULTLINE="$faultline" "$root/examples/slurm/submit.sh" "$journal" "$out/results" "$n" "$data" \
        >"$out/submit.out" 2>&1; then
    echo "FAIL: submitting failed:" >&2
    cat "$out/submit.out" >&2
    exit 1
fi
merge=$(sed -n 's/^merge: job \([0-9]*\).*/\1/p' "$out/submit.out")
state=""
for _ in $(seq 600); do
    state=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
    case "$state" in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) break ;; esac
    sleep 0.5
done
sharded=$(echo "$(date +%s.%N) - $start" | bc)
if [ "$state" != COMPLETED ]; then
    echo "FAIL: the merge job ended $state; job output:" >&2
    cat "$out/submit.out" "$out"/results/*.out >&2 || true
    exit 1
fi
status=0
count=0
for csv in "$out"/whole/*.csv; do
    name=$(basename "$csv")
    count=$((count + 1))
    cmp -s "$csv" "$out/results/$name" || { echo "FAIL: merged $name differs from the whole run's" >&2; status=1; }
done
[ "$count" -gt 0 ] || { echo "FAIL: the journal wrote no CSV" >&2; status=1; }
[ "$status" -eq 0 ] && printf 'slurm: %d shards merged into %d CSVs equal to the whole run; whole %.1f s, on Slurm %.1f s (%d CPUs)\n' \
    "$n" "$count" "$whole" "$sharded" "$cpus"
exit "$status"
