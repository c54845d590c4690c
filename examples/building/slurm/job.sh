#!/bin/sh
# One shard of a building, as one task of a Slurm job array: task I of an array of N builds
# shard I/N (`eigenrad building --shard`) and writes its rooms' parts into OUT/parts/.
# Submitted by submit.sh; every task sees the same OUT (a shared file system).
#
#   sbatch --array=0-3 job.sh MANIFEST OUT
#
#SBATCH --job-name=eigenrad-rooms
#SBATCH --cpus-per-task=1
set -eu
manifest=$1
out=$2
: "${SLURM_ARRAY_TASK_ID:?run me as a task of a job array (sbatch --array)}"
: "${SLURM_ARRAY_TASK_COUNT:?run me as a task of a job array (sbatch --array)}"
exec "${EIGENRAD:-eigenrad}" building "$manifest" --out "$out" \
    --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT"
