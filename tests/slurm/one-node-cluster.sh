#!/bin/sh
# A one-node Slurm cluster on this machine, in a folder of its own (tests labelled slurm):
#   one-node-cluster.sh start DIR   munged with a generated key, slurmctld and slurmd with a
#                                   generated slurm.conf on localhost (ports of their own), all
#                                   state in DIR; waits until the node is idle. Prints the
#                                   SLURM_CONF clients need.
#   one-node-cluster.sh stop DIR    stops slurmd, slurmctld and munged by their pid files.
# Needs root (the daemons run as root: SlurmUser=root) and Debian's slurm-wlm and munge.
set -u
what="$1"
dir="$2"

stop_pid() {
    if [ -f "$1" ]; then
        pid=$(cat "$1")
        if [ -n "$pid" ] && kill "$pid" 2>/dev/null; then
            i=0
            while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
            kill -9 "$pid" 2>/dev/null
        fi
        rm -f "$1"
    fi
}

if [ "$what" = stop ]; then
    stop_pid "$dir/slurmd.pid"
    stop_pid "$dir/slurmctld.pid"
    stop_pid "$dir/munged.pid"
    exit 0
fi

[ "$what" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
for program in munged slurmctld slurmd sinfo; do
    command -v "$program" >/dev/null || { echo "$program is not installed (scripts/setup installs slurm-wlm and munge)" >&2; exit 77; }
done
[ "$(id -u)" = 0 ] || { echo "the one-node cluster needs root" >&2; exit 77; }

mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
chmod 0700 "$dir/munge"
head -c 1024 /dev/urandom > "$dir/munge/munge.key"
chmod 0400 "$dir/munge/munge.key"
munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munge.seed" --force || { echo "munged did not start" >&2; exit 1; }

host=$(hostname -s)
# Ports of our own (never another Slurm's): from the folder's name, in 20000..29999.
port=$((20000 + $(printf '%s' "$dir" | cksum | cut -d' ' -f1) % 5000 * 2))
cpus=$(nproc)
cat > "$dir/slurm.conf" <<CONF
ClusterName=bender-test
SlurmctldHost=$host
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MessageTimeout=30
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=bender Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" -i || { echo "slurmctld did not start (see $dir/log)" >&2; exit 1; }
slurmd -f "$SLURM_CONF" || { echo "slurmd did not start (see $dir/log)" >&2; exit 1; }
i=0
until sinfo -h -o %T 2>/dev/null | grep -q idle; do
    i=$((i + 1))
    if [ $i -gt 300 ]; then
        echo "the node did not become idle in 30 s (see $dir/log)" >&2
        exit 1
    fi
    sleep 0.1
done
echo "$SLURM_CONF"
