"""A study's runs as separate jobs (cases/studies/jobs.py): planned by `run.py --plan`, made by the processes of
`mpirun -n 2` (each its share, each lagfsi run alone, not one MPI run of two processes) and by one job-array task
(`--index`), then collected by the study without a single run of its own.

Usage: test_study_jobs.py MPIEXEC OUTDIR [EXE]   (a failed check exits 1 with what failed)"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
STUDIES = os.path.join(HERE, "..", "..", "cases", "studies")
PY = sys.executable
mpiexec, out = sys.argv[1], os.path.abspath(sys.argv[2])
exe = ["--exe", sys.argv[3]] if len(sys.argv) > 3 else []
study = [PY, os.path.join(STUDIES, "alpha_sensitivity", "run.py"), "--quick", "--no-nice", "--out", out] + exe
jobs = [PY, os.path.join(STUDIES, "jobs.py")]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAILED:", what)


def run(cmd, **kw):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=300,
                       **kw)
    print("$", " ".join(cmd), "\n" + p.stdout)
    return p


def plan(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


subprocess.call(["rm", "-rf", out])
os.makedirs(out)
p1 = os.path.join(out, "plan1.jsonl")
r = run(study + ["--plan", p1])
check(r.returncode == 0, "the planning run exits 0")
first = plan(p1)
check(len(first) == 3, "the quick study plans its 3 runs (got %d)" % len(first))
check(not os.listdir(os.path.join(out, "results_quick")), "planning writes no table or chart")
check(all(not os.path.isdir(j["out"]) for j in first), "planning makes no run")

# The last job is left to a job-array task; the others to two MPI processes.
p2 = os.path.join(out, "plan2.jsonl")
with open(p2, "w") as f:
    f.writelines(json.dumps(j) + "\n" for j in first[:-1])
r = run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-np", "2", "-x", "OMP_NUM_THREADS=1"] + jobs + [p2])
check(r.returncode == 0, "mpirun -n 2 jobs.py exits 0")
done = sorted(line.split()[1:4:2] for line in r.stdout.splitlines() if line.startswith("[rank"))
check(done == [["0]", "0:"], ["1]", "1:"]], "each process makes its own job (rank 0 job 0, rank 1 job 1): %s" % done)
r = run(jobs + [p1, "--count"])
check(r.stdout.strip() == "3", "--count gives the plan's size")
r = run(jobs + [p1, "--index", "2"])
check(r.returncode == 0 and "job 2:" in r.stdout, "--index 2 makes job 2")
r = run(jobs + [p1, "--index", "3"])
check(r.returncode != 0 and "--index 3" in r.stdout, "an index past the plan is refused in one line")
for j in first:
    with open(os.path.join(j["out"], "study_run.json")) as f:
        check(json.load(f)["rc"] == 0, "job %s's run succeeded" % j["out"])

r = run(study + ["--plan", os.path.join(out, "plan3.jsonl")])
check(r.returncode == 0 and plan(os.path.join(out, "plan3.jsonl")) == [], "planning again: nothing left to run")
r = run(study)
check(r.returncode == 0, "the study collects the runs")
with open(os.path.join(out, "results_quick", "meta.json")) as f:
    meta = json.load(f)
check(meta["runs"] == 3 and meta["runs_reused"] == 3, "the study reuses the 3 runs and makes none: %s" % meta)
bad = os.path.join(out, "bad.jsonl")
with open(bad, "w") as f:
    f.write('{"cmd": "lagfsi"}\n')
r = run(jobs + [bad])
check(r.returncode != 0 and "bad.jsonl:1: not a job" in r.stdout, "a malformed plan line is refused with its line")
print("%d failed" % len(failures) if failures else "all passed")
sys.exit(1 if failures else 0)
