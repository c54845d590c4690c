#!/bin/sh
# Builds a building on a Slurm cluster: a job array of SHARDS tasks, one shard of the rooms
# each, then the merge, chained with --dependency=afterok so that it runs only once every
# task has succeeded. Prints the two job ids (array, merge).
#
#   examples/building/slurm/submit.sh MANIFEST OUT [SHARDS]
#
# SHARDS defaults to 4 (at most the number of rooms). OUT must be on a file system every node
# sees. EIGENRAD names the eigenrad binary (default: `eigenrad` on the PATH); extra sbatch
# options (a partition, an account) go in SBATCH_OPTIONS.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
manifest=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
mkdir -p "$2"
out=$(cd "$2" && pwd)
shards=${3:-4}
# The logs of every task go next to the parts.
mkdir -p "$out/logs"
# shellcheck disable=SC2086 # SBATCH_OPTIONS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="0-$((shards - 1))" \
    --output="$out/logs/rooms-%a.out" --export=ALL \
    "$here/job.sh" "$manifest" "$out")
array=${array%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterok:$array" \
    --kill-on-invalid-dep=yes --output="$out/logs/merge.out" --export=ALL \
    "$here/merge.sh" "$manifest" "$out")
merge=${merge%%;*}
echo "$array $merge"
