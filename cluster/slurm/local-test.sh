#!/usr/bin/env bash
# Opt-in: runs grinlight's Slurm recipe for real on this one machine and checks its result.
#
# Starts a single-node Slurm (munge, slurmctld, slurmd; installed with apt-get if missing,
# which needs root), then for each scene renders it once in one process and once as a job
# array of N shards with a dependent merge job (cluster/slurm/submit.sh), checks that the
# merged files equal the single run's byte for byte, and prints the wall times with the
# machine's core count. Stops the daemons it started. Not part of CI (it needs root and a
# few minutes).
#
#   cluster/slurm/local-test.sh            # N = 2 and 4 shards
set -euo pipefail
repo=$(realpath "$(dirname "$0")/../..")
cores=$(nproc)
if ! command -v slurmctld >/dev/null; then
    apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null
fi
(cd "$repo" && cargo build --release --quiet)
export GRINLIGHT=$repo/target/release/grinlight

work=$(mktemp -d /tmp/grinlight-slurm.XXXXXX)
host=$(hostname)
memory=$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<CONF
ClusterName=grinlight-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=$host CPUs=$cores RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf

mkdir -p /run/munge
chown munge:munge /run/munge 2>/dev/null || true
started_munge=
if ! pgrep -x munged >/dev/null; then
    [[ -s /etc/munge/munge.key ]] || mungekey --create >/dev/null 2>&1 || create-munge-key >/dev/null
    runuser -u munge -- munged
    started_munge=1
fi
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
stop() {
    kill "$(cat "$work/slurmd.pid" 2>/dev/null)" "$(cat "$work/slurmctld.pid" 2>/dev/null)" 2>/dev/null || true
    [[ -n $started_munge ]] && pkill -x munged || true
}
trap stop EXIT
for _ in $(seq 100); do
    sinfo -h -o %T 2>/dev/null | grep -q idle && break
    sleep 0.2
done
echo "single-node Slurm $(sinfo -V | cut -d' ' -f2) up: $(sinfo -h -o '%N %c CPUs %T')"

# Waits for every job of this run to leave the queue.
wait_queue() {
    while [[ -n $(squeue -h -o %i) ]]; do sleep 0.2; done
}

# Renders a scene as N shards through the queue: the job array and its merge job.
shards() {
    local n=$1 out=$2 scene=$3
    shift 3
    "$repo/cluster/slurm/submit.sh" "$scene" "$n" "$out" "$@" >/dev/null
    wait_queue
}

source "$repo/cluster/compare.sh"
compare_all Slurm
echo
echo "machine: $cores cores; on $cores cores N shards can run at most $cores at once, so the"
echo "Slurm run's speed-up over one process with 1 thread is at most $cores×, and it cannot beat one"
echo "process using all $cores threads: the point is exactness and the recipe, not speed here."
echo "work files: $work"
