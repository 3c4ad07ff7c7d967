#!/bin/bash
# Runs a journal over a run's frames as a Slurm job array of N shards, then merges the results.
#   examples/slurm/submit.sh [--wait] JOURNAL OUT N [DATA]
# JOURNAL  the recorded analysis (.jsonl; exports over time, per-frame renders)
# OUT      results folder on a file system every node sees (shards write OUT/shard-K)
# N        number of shards (array tasks); each takes every N-th frame
# DATA     optional: the run's files instead of the journal's (replay --data)
# --wait   return when the merge is done (its exit status), as the test does
# FAULTLINE (environment) names the faultline binary if it is not on PATH; extra sbatch options
# (partition, account, time) go in SBATCH_* variables, e.g. SBATCH_PARTITION=short.
set -euo pipefail
wait=()
if [ "${1:-}" = "--wait" ]; then wait=(--wait); shift; fi
if [ $# -lt 3 ]; then
    sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
journal=$(realpath "$1")
out=$(realpath -m "$2")
n=$3
data=${4:+$(realpath "$4")}
faultline=${FAULTLINE:-$(command -v faultline || true)}
[ -x "$faultline" ] || { echo "faultline not found: set FAULTLINE=/path/to/faultline" >&2; exit 2; }
mkdir -p "$out"
env_vars="ALL,JOURNAL=$journal,OUT=$out,DATA=$data,FAULTLINE=$faultline"
array=$(sbatch --parsable --array="1-$n" --chdir="$out" --export="$env_vars" \
    "$here/faultline-shard.sbatch")
echo "shards: job array $array (1-$n)"
merge=$(sbatch --parsable "${wait[@]}" --dependency="afterok:$array" --kill-on-invalid-dep=yes \
    --chdir="$out" --export="$env_vars" "$here/faultline-merge.sbatch")
echo "merge: job $merge (after the array succeeds)"
