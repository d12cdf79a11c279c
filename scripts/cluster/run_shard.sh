#!/usr/bin/env bash
# Runs shard K of N of a nightly batch into OUT/shard_K, the same way on every cluster
# (slurm_batch.sbatch, k8s_indexed_job.yaml). A shard that was killed and is started again
# (Slurm requeue, Kubernetes pod restart) resumes: it runs exactly the runs not done.
#
# Usage: run_shard.sh K N OUT INPUT...   (INPUT: logical scenarios or parameter files)
# Env:   ORCHESTRATOR (default: orchestrator in PATH), JOBS (default: all cores of the task)
#
# Exit status: 0 when the shard's batch ran to its end -- whatever the verdicts, which the
# merged summary and JUnit file report -- so that the scheduler does not retry failed
# tests; otherwise the batch's own status (3: interrupted, to be resumed).
set -uo pipefail
if [ $# -lt 4 ]; then
  echo "usage: $0 K N OUT INPUT..." >&2
  exit 64
fi
k=$1 n=$2 out=$3
shift 3
orchestrator=${ORCHESTRATOR:-orchestrator}
jobs_opt=()
[ -n "${JOBS:-}" ] && jobs_opt=(--jobs "$JOBS")
dir="$out/shard_$k"
mkdir -p "$out"
if [ -f "$dir/batch.json" ]; then
  "$orchestrator" batch --resume "$dir" "${jobs_opt[@]}"
else
  "$orchestrator" batch "$@" --shard "$k/$n" --out "$dir" "${jobs_opt[@]}"
fi
status=$?
# 0 all passed, 1 some failed, 2 some could not run: the batch is complete either way.
if [ "$status" -le 2 ]; then
  exit 0
fi
exit "$status"
