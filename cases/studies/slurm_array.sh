#!/bin/bash
# One task of a study plan's job array on a Slurm cluster (cases/studies/jobs.py). From the repository root:
#   /usr/bin/python3 cases/studies/<study>/run.py --plan plan.jsonl [--exe PATH --out DIR ...]
#   sbatch --array=0-$(( $(/usr/bin/python3 cases/studies/jobs.py plan.jsonl --count) - 1 )) \
#          cases/studies/slurm_array.sh plan.jsonl
# and when the array has finished, the same run.py without --plan writes the tables and charts (with
# `sbatch --dependency=afterok:<array id>` it can be a job of its own). Each task is one single-threaded lagfsi run.
#SBATCH --job-name=lagfsi-study
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
set -euo pipefail
cd "${SLURM_SUBMIT_DIR:-.}"
exec /usr/bin/python3 cases/studies/jobs.py "$@" --index "${SLURM_ARRAY_TASK_ID:?not a Slurm array task}"
