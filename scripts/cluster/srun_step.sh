#!/usr/bin/env bash
# Starts one run (the program and its arguments) as a Slurm job step of the current
# allocation: one task on one CPU of its own (--exclusive: steps started together get
# different CPUs, and a step waits while every CPU is busy). The --wrapper of a batch or a
# search inside an sbatch job (slurm_search.sbatch). Extra srun options: ORCH_SRUN_OPTIONS
# (e.g. --mem-per-cpu=2G where the cluster tracks memory).
set -euo pipefail
# shellcheck disable=SC2086
exec srun --ntasks=1 --nodes=1 --cpus-per-task=1 --exclusive --quiet ${ORCH_SRUN_OPTIONS:-} "$@"
