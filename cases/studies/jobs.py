"""Runs the jobs of study plans (`run.py --plan FILE`) as separate jobs: a batch scheduler's job array or the MPI
launcher, not a pool of this script's own.

Usage: /usr/bin/python3 cases/studies/jobs.py PLAN [PLAN ...] [--index I] [--count]
  --index I   run job I only (0-based, over the plans in the order given): one task of a job array, e.g. Slurm's
              `--index $SLURM_ARRAY_TASK_ID` (cases/studies/slurm_array.sh)
  --count     print the number of jobs and exit (the array's size)
  neither     every job; under `mpirun -n P` each of the P processes runs the jobs whose number modulo P is its rank
              (read from the launcher's environment: Open MPI's OMPI_COMM_WORLD_RANK/SIZE, MPICH's PMI_RANK/SIZE or
              srun's SLURM_PROCID/SLURM_NTASKS), one after the other
Each job is one lagfsi run into its own folder with the record its study reuses (runjob.py), so after the jobs,
`run.py` without --plan finds every run finished and writes the tables and charts. A job whose run fails is a
result for its study (a stability map's failures are its data): the exit code is non-zero only when a job could
not be read or started."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runjob  # noqa: E402


def rank_size():
    """This process's rank and the number of processes of its launch (0, 1 outside a launcher)."""
    for r, n in (("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"), ("PMI_RANK", "PMI_SIZE"),
                 ("SLURM_PROCID", "SLURM_NTASKS")):
        if r in os.environ and n in os.environ:
            return int(os.environ[r]), int(os.environ[n])
    return 0, 1


def read_plans(paths):
    jobs = []
    for path in paths:
        with open(path) as f:
            for k, line in enumerate(f, 1):
                if not line.strip():
                    continue
                try:
                    job = json.loads(line)
                    if not isinstance(job.get("cmd"), list) or not isinstance(job.get("out"), str):
                        raise ValueError("a job needs 'cmd' (a list) and 'out' (a folder)")
                except ValueError as e:
                    sys.exit("%s:%d: not a job: %s" % (path, k, e))
                jobs.append(job)
    return jobs


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("plans", nargs="+", metavar="PLAN")
    ap.add_argument("--index", type=int, default=None)
    ap.add_argument("--count", action="store_true")
    a = ap.parse_args(argv)
    try:
        jobs = read_plans(a.plans)
    except OSError as e:
        sys.exit("jobs.py: %s" % e)
    if a.count:
        print(len(jobs))
        return 0
    if a.index is not None:
        if not 0 <= a.index < len(jobs):
            sys.exit("jobs.py: --index %d: the plans hold %d jobs (0 to %d)" % (a.index, len(jobs), len(jobs) - 1))
        mine = [a.index]
        rank = 0
    else:
        rank, size = rank_size()
        mine = list(range(rank, len(jobs), size))
    for i in mine:
        job = jobs[i]
        try:
            rec = runjob.execute(job)
        except OSError as e:
            sys.exit("jobs.py: job %d (%s): %s" % (i, job["out"], e))
        print("[rank %d] job %d: %s rc=%d %.1f s" % (rank, i, os.path.basename(job["out"]), rec["rc"], rec["wall"]),
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
