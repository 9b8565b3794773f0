#!/usr/bin/env bash
# Runs a study on a Slurm cluster: a job array with one shard per task, then a merge
# job that waits for all of them (docs/CLUSTER.md).
#
#   scripts/slurm_study.sh STUDY.json OUT_DIR SHARDS [sbatch options...]
#
# e.g. scripts/slurm_study.sh cases/paper_study.json /scratch/$USER/paper 3 \
#          --cpus-per-task=16 --time=12:00:00 --requeue
#
# Task K runs `ballast study STUDY.json -o OUT_DIR/shard-K-of-N.h5 --shard K/N --resume`
# on the task's CPUs (SLURM_CPUS_PER_TASK, else 1), logging to OUT_DIR/shard-K-of-N.log.
# --resume makes a requeued or resubmitted task finish its shard instead of starting
# again. The merge job (afterany: it also runs when a task failed or ran out of time,
# and then names the missing runs) writes OUT_DIR/<study name>.h5; run again with the
# same OUT_DIR (after a failure), it first moves the earlier merge aside to
# OUT_DIR/<study name>.h5.before-job-ID, since `ballast merge` refuses an -o that exists.
# BALLAST: the ballast binary (default: build/study/ballast next to this script).
# Prints the two job ids.
set -euo pipefail

if [ $# -lt 3 ]; then
  sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
study=$(realpath "$1")
out=$(realpath -m "$2")
shards=$3
shift 3
case $shards in
  '' | *[!0-9]* | 0) echo "slurm_study.sh: SHARDS must be a positive integer, got '$shards'" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "$0")" && pwd)
ballast=$(realpath "${BALLAST:-$here/../build/study/ballast}")
[ -x "$ballast" ] || { echo "slurm_study.sh: no ballast binary at $ballast (make build, or set BALLAST)" >&2; exit 2; }
# Refuse a bad study now rather than in N jobs tomorrow.
"$ballast" study "$study" --dry-run > /dev/null
name=$(basename "$study" .json)
mkdir -p "$out"

shard="$out/shard-\${SLURM_ARRAY_TASK_ID}-of-$shards"
array=$(sbatch --parsable --job-name="$name" --array="1-$shards" \
  --output="$out/shard-%a-of-$shards.log" "$@" \
  --wrap="OMP_NUM_THREADS=\${SLURM_CPUS_PER_TASK:-1} '$ballast' study '$study' -o \"$shard.h5\" --shard \${SLURM_ARRAY_TASK_ID}/$shards --resume --progress plain")
array=${array%%;*}
merged="$out/$name.h5"
aside="$merged.before-job-\${SLURM_JOB_ID}"
merge=$(sbatch --parsable --job-name="$name-merge" --dependency="afterany:$array" \
  --output="$out/merge.log" "$@" \
  --wrap="if [ -e '$merged' ]; then mv '$merged' \"$aside\" && echo \"moved the earlier merge aside: $aside\"; fi; '$ballast' merge $(for k in $(seq 1 "$shards"); do printf "'%s' " "$out/shard-$k-of-$shards.h5"; done)-o '$merged'")
merge=${merge%%;*}
echo "array job $array ($shards shards), merge job $merge -> $out/$name.h5"
