"""One run of a study: the lagfsi command, executed into its folder with the record (`study_run.json`) that lets the
study reuse it. Shared by a study's own runs (common.Study.run) and the jobs of a plan (jobs.py), so that a run made by
a batch job or under mpirun is the run the study would have made itself. No third-party import: a compute node needs
only Python 3.

A job is a dict: cmd (the lagfsi command line), out (its folder), timeout (s or None), nice (run under nice -n 19)."""
import json
import os
import resource
import subprocess
import time

STAMP = "study_run.json"


def clear(out):
    """Empties (or creates) a run folder."""
    if os.path.isdir(out):
        for root, dirs, files in os.walk(out, topdown=False):
            for f in files:
                os.remove(os.path.join(root, f))
            for d in dirs:
                os.rmdir(os.path.join(root, d))
    os.makedirs(out, exist_ok=True)


def solo_environment():
    """This process's environment without an MPI launcher's variables: a job started by a process of `mpirun -n P`
    would otherwise find them, take itself for one of P processes of an MPI run and wait for the others."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "PMI_", "MPI_LOCALRANKID",
                                                                      "HYDRA_"))}


def execute(job):
    """Runs the job into its (emptied) folder, alone (solo_environment), and writes its record there; returns the
    record (cmd, exe_mtime, rc, wall, cpu, load_before, stderr). rc -1: killed at the timeout."""
    cmd, out, timeout = list(job["cmd"]), job["out"], job.get("timeout")
    exe_mtime = os.path.getmtime(cmd[0])
    clear(out)
    full = ["nice", "-n", "19"] + cmd if job.get("nice", True) else cmd
    load = os.getloadavg()[0]
    t = time.time()
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        p = subprocess.run(full, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout,
                           universal_newlines=True, env=solo_environment())
        rc, err = p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        rc, err = -1, "timeout after %s s" % timeout
    wall = time.time() - t
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)  # the run's own, whatever shares the machine
    record = {"cmd": cmd, "exe_mtime": exe_mtime, "rc": rc, "wall": wall, "cpu": cpu, "load_before": load,
              "stderr": err[-2000:]}
    with open(os.path.join(out, STAMP), "w") as f:
        json.dump(record, f, indent=1)
    return record


def run_key(cmd):
    """The command with the case file named relative to its cases folder (the same case in another checkout of the
    same commit is the same run)."""
    k = list(cmd)
    if len(k) > 2 and "/cases/" in k[2]:
        k[2] = k[2].split("/cases/")[-1]
    return k


def finished(cmd, out):
    """The record of a finished run of `cmd` in `out` made by the executable as it is now, or None."""
    stamp = os.path.join(out, STAMP)
    if not os.path.isfile(stamp) or not os.path.isfile(os.path.join(out, "summary.json")):
        return None
    try:
        with open(stamp) as f:
            old = json.load(f)
    except (OSError, ValueError):
        return None
    exe_mtime = os.path.getmtime(cmd[0])
    if run_key(old.get("cmd", [])) == run_key(cmd) and old.get("exe_mtime", exe_mtime) == exe_mtime:
        return old
    return None
