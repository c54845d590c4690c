#!/bin/sh
# The merge of a building: every controller's basis from the rooms' parts in OUT/parts/,
# written into OUT. Submitted by submit.sh to start once every shard has succeeded.
#
#SBATCH --job-name=eigenrad-merge
#SBATCH --cpus-per-task=1
set -eu
exec "${EIGENRAD:-eigenrad}" merge "$1" --out "$2"
