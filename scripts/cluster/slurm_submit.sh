#!/usr/bin/env bash
# Submits a nightly batch to Slurm: a job array of N shards, then a merge job that runs
# when every shard has ended (afterany: also when one crashed, so the report says so).
#
# Usage: scripts/cluster/slurm_submit.sh N OUT INPUT...
# Env:   ORCHESTRATOR (the binary, on every node), extra sbatch options in SBATCH_OPTIONS.
# The merged summary.json, junit.xml and summary.txt land in OUT/merged.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 N OUT INPUT..." >&2
  exit 64
fi
here=$(cd "$(dirname "$0")" && pwd)
n=$1 out=$(readlink -f "$2")
shift 2
inputs=()
for f in "$@"; do inputs+=("$(readlink -f "$f")"); done
orchestrator=${ORCHESTRATOR:-$(command -v orchestrator)}
mkdir -p "$out"
# shellcheck disable=SC2086
array=$(ORCHESTRATOR=$orchestrator ORCH_CLUSTER_SCRIPTS=$here sbatch --parsable ${SBATCH_OPTIONS:-} \
  --array="1-$n" --chdir="$out" --export=ALL "$here/slurm_batch.sbatch" "$out" "${inputs[@]}")
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterany:$array" --job-name=orch-nightly-merge \
  --chdir="$out" --output="$out/merge-%j.out" \
  --wrap="'$orchestrator' batch merge '$out'/shard_* --out '$out/merged'")
echo "shards: job array $array (1-$n); merge: job $merge; results: $out/merged"
