"""An MPI run of a fluid case (mpirun -n P lagfsi run; src/core/include/lagfsi/mpi_run.hpp): replicated data,
distributed solves. Run by CTest as
  /usr/bin/python3 test_mpi_run.py LAGFSI MPIEXEC CASE.json WORKDIR [lagfsi run arguments ...]
(the extra arguments, e.g. --set key=value, are given to every run).
Checks, on the first 0.1 s of the case with the PETSc solver:
  - one process under mpirun gives the serial run's probes bit for bit;
  - two and three processes give the serial mesh at every step (log.csv: the same step sizes, nodes and elements)
    and probes within the Krylov tolerance of the serial run's (relative to each column's largest value);
  - process 0 alone writes the CSV files and summary.json (which says how many processes ran, and that the remeshing
    was divided among them with a ghost layer); the fluid's series
    is parallel VTK: every step a .pvtu whose pieces (one per process) hold together the serial run's elements and
    particles;
  - bad input stops every process with one message and exit code 2.
Exits non-zero with the failed checks listed."""
import csv
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "tools"))
from lagfsi_post import vtkxml  # noqa: E402

exe, mpiexec, case, work = sys.argv[1:5]
extra_args = sys.argv[5:]
MPI = [mpiexec, "--allow-run-as-root", "--oversubscribe", "-np"]
COMMON = ["-q", "--threads", "1", "--set", "analysis.end_time=0.1",
          "--set", "bodies.0.scheme.linear_solver=petsc"] + extra_args
failures = []


def run(tag, processes=None, extra=()):
    out = os.path.join(work, tag)
    shutil.rmtree(out, ignore_errors=True)
    cmd = ([] if processes is None else MPI + [str(processes)]) + [exe, "run", case, "-o", out] + COMMON + list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode != 0:
        failures.append("%s: exit %d: %s" % (tag, p.returncode, p.stderr.strip()[-400:]))
    return out


def table(path):
    with open(path) as f:
        return list(csv.DictReader(f))


os.makedirs(work, exist_ok=True)
serial = run("serial")
one = run("np1", 1)
with open(os.path.join(serial, "probes.csv"), "rb") as a, open(os.path.join(one, "probes.csv"), "rb") as b:
    if a.read() != b.read():
        failures.append("one process: probes.csv differs from the serial run's")
ref_log, ref_probes = table(os.path.join(serial, "log.csv")), table(os.path.join(serial, "probes.csv"))
for n in (2, 3):
    out = run("np%d" % n, n)
    log, probes = table(os.path.join(out, "log.csv")), table(os.path.join(out, "probes.csv"))
    if len(log) != len(ref_log):
        failures.append("%d processes: %d steps, the serial run %d" % (n, len(log), len(ref_log)))
    for a, b in zip(ref_log, log):
        if (a["dt"], a["nodes"], a["elements"]) != (b["dt"], b["nodes"], b["elements"]):
            failures.append("%d processes: step %s meshes %s/%s nodes/elements, the serial run %s/%s"
                            % (n, a["step"], b["nodes"], b["elements"], a["nodes"], a["elements"]))
            break
    for col in ref_probes[0]:
        scale = max(abs(float(r[col])) for r in ref_probes) or 1.0
        diff = max(abs(float(a[col]) - float(b[col])) for a, b in zip(ref_probes, probes)) / scale
        if diff > 1e-6:
            failures.append("%d processes: probe %s differs by %.2e of its largest value" % (n, col, diff))
    # Parallel VTK: the fluid's .pvd lists one .pvtu a step, with one piece a process; merged, the serial step.
    serial_steps, steps = vtkxml.read_pvd(os.path.join(serial, "water.pvd")), vtkxml.read_pvd(os.path.join(out, "water.pvd"))
    if len(steps) != len(serial_steps) or not all(f.endswith(".pvtu") for _, f in steps):
        failures.append("%d processes: water.pvd lists %d steps (%s), the serial run %d .vtu"
                        % (n, len(steps), steps[:1], len(serial_steps)))
    for (t, f), (_, g) in zip(steps, serial_steps):
        with open(f) as pv:
            pieces = pv.read().count("<Piece ")
        merged, whole = vtkxml.read_vtk(f), vtkxml.read_vtk(g)
        if (pieces != n or len(merged.triangles()) != len(whole.triangles()) or
                set(merged.point_data["particle_id"].astype(int)) != set(whole.point_data["particle_id"].astype(int))):
            failures.append("%d processes: %s has %d pieces, %d elements and %d particles; the serial step %d and %d"
                            % (n, os.path.basename(f), pieces, len(merged.triangles()),
                               len(set(merged.point_data["particle_id"])), len(whole.triangles()),
                               len(set(whole.point_data["particle_id"]))))
            break
    import json
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary.get("mpi_processes") != n:
        failures.append("%d processes: summary.json does not say mpi_processes = %d" % (n, n))
    # The remeshing divided among the processes: a ghost layer, some but not all of the particles, per process.
    divided = summary["bodies"][0]["remeshing"].get("divided", {})
    if divided.get("processes") != n or not 0 < divided.get("ghost_share", 0) < n - 1:
        failures.append("%d processes: summary.json's divided remeshing %s" % (n, divided))
    # Each process's report: its phases, some communication, its memory; process 0's communication in the log.
    procs = summary.get("processes", [])
    if ([q.get("rank") for q in procs] != list(range(n)) or
            not all(q["solve"] > 0 and q["comm"] > 0 and q["comm_MB"] > 0 and q["petsc_MB"] > 0 and q["peak_MB"] > 0
                    and 0 < q["halo"] < q["factorization"] + q["solve"]
                    and q["remesh"] + q["assembly"] + q["factorization"] + q["solve"] <= q["wall"] for q in procs)):
        failures.append("%d processes: summary.json's processes %s" % (n, procs))
    if not all(float(r["comm_MB"]) > 0 and float(r["t_comm"]) >= 0 and 0 <= float(r["t_halo"]) <= float(r["t_step"])
               for r in log):
        failures.append("%d processes: log.csv's communication columns %s" % (n, log[0]))

# Bad input: every process stops, one message (mpirun's own report aside), exit code 2.
p = subprocess.run(MPI + ["2", exe, "run", case, "-o", os.path.join(work, "bad"), "--set", "analysis.dt=-1"],
                   capture_output=True, text=True)
lines = [l for l in p.stderr.splitlines() if l.startswith("lagfsi:")]
if p.returncode != 2 or len(lines) != 1:
    failures.append("bad input under mpirun: exit %d, %d lagfsi lines: %s" % (p.returncode, len(lines), lines))

if failures:
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("mpi run: 1 process bit for bit, 2 and 3 processes the serial mesh at every step and probes within 1e-6")
