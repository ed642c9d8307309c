#!/usr/bin/env bash
# Submits a grinlight render to Slurm as a job array of N shards and a merge that runs when
# every shard has succeeded; prints the two job ids.
#
#   cluster/slurm/submit.sh SCENE N OUT [render options...]
#
# OUT must be a directory every node sees (a shared file system). Set GRINLIGHT to the
# binary's path if it is not on the nodes' PATH; pass sbatch options (partition, time,
# account) in SBATCH_* environment variables (e.g. SBATCH_PARTITION), which sbatch reads.
set -euo pipefail
if [[ $# -lt 3 ]]; then
    echo "usage: $0 SCENE N OUT [render options...]" >&2
    exit 2
fi
scene=$(realpath "$1")
n=$2
out=$(realpath "$3")
shift 3
here=$(dirname "$(realpath "$0")")
mkdir -p "$out"
array=$(sbatch --parsable --array="1-$n" --output="$out/shard-%a.log" \
    "$here/render.sbatch" "$scene" "$out" "$@")
merge=$(sbatch --parsable --dependency="afterok:${array%%;*}" --output="$out/merge.log" \
    "$here/merge.sbatch" "$out" "$n")
echo "shards: job $array (array 1-$n); merge: job $merge"
