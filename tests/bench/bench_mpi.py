#!/usr/bin/python3
"""Benchmark (not a test): a fluid step over MPI processes against the same step on one process.

Runs `lagfsi run cases/dam_break_tank/case.json` with the spacing h = 0.0073 sqrt(861 / N) for each target particle
count N and dt scaled with h (as tests/bench/bench_scaling.py), the monolithic scheme with the PETSc solver
(FGMRES + Schur field split), one thread per process, a few steps from rest: serially (no launcher), under
`mpirun -np 1` and under `mpirun -np P` for each P given. The processes hold every particle (replicated data,
src/core/include/lagfsi/mpi_run.hpp); the linear solves, the element assembly and the remeshing's triangulation and
domain detection are divided among them, the particle management is not. Per run, from process 0's log.csv over the steps after the first
`--warmup`: microseconds per particle-step in all and by phase (remesh, assembly with the combination of the
residual's rows over the processes, solver set-up, solve, rest) and the speed-up against the one-process MPI run of
the same size (wall time per step, measured in this one invocation), the Newton iterations a step and that speed-up
per Newton iteration; from summary.json, the Krylov iterations a solve, the divided remeshing's ghost share and the
mesh data process 0 receives a remesh; the same measures of P serial runs of N / P particles started together,
whose time a step against the one-process run's bounds the speed-up of a perfect division of the work among P
processes on this machine (its shared cores, caches and memory; `--no-bound` leaves them out); and the memory
bandwidth of one process alone and of each of P at once (the STREAM triad of tests/bench/bench_bandwidth.cpp).

usage: /usr/bin/python3 tests/bench/bench_mpi.py [OUTDIR] [--build DIR] [--sizes 1e5 1e6] [--processes 2]
           [--steps 8] [--warmup 2] [--scheme monolithic_pspg|fractional_step] [--doc docs/running.md]
           [--marker bench_mpi] [--no-bound]
--doc: rewrite the table between the markers <!-- MARKER begin --> and <!-- MARKER end --> of that file.
--weak N ...: weak scaling instead, one process at N particles against P processes at P N and against P serial runs
of N at once (marker bench_mpi_weak).
Sizes past the 2 million nodes a mesh may have by default pass --max-nodes.
Run it on an otherwise idle machine: P processes need P free cores.
OUTDIR (default BUILD/bench_mpi/) receives bench_mpi.csv and the runs' output folders.
"""
import argparse
import csv
import json
import os
import platform
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(REPO, "cases", "dam_break_tank", "case.json")
H0, N0, DT = 0.0073, 861, 1e-3
PHASES = [("remesh", "t_remesh"), ("assembly", "t_assembly"), ("setup", "t_factorization"), ("solve", "t_solve")]
COLUMNS = ["launch", "processes", "target", "particles", "steps", "us_per_particle_step", "remesh", "assembly",
           "setup", "solve", "rest", "peak_mb", "speedup", "newton_per_step", "krylov_per_solve", "speedup_per_iteration",
           "ghost_share", "gathered_mb", "comm_share", "halo_share", "comm_mb_per_step"]


def start(exe, outdir, launch, processes, n, steps, warmup, scheme, copy=None):
    """Launches one run (`copy`: the number of one of several serial runs at once); finish() reads it."""
    h = H0 * (N0 / n) ** 0.5
    dt = DT * h / H0
    tag = f"{launch}_np{processes}_n{int(n)}_{scheme}" + (f"_copy{copy}" if copy is not None else "")
    out = os.path.join(outdir, tag)
    shutil.rmtree(out, ignore_errors=True)
    mpi = [] if launch != "mpirun" else [shutil.which("mpirun") or "mpirun", "--allow-run-as-root", "--oversubscribe",
                                         "-np", str(processes)]
    args = (["/usr/bin/time", "-f", "%M"] + mpi +
            [exe, "run", CASE, "-o", out, "--quiet", "--threads", "1",
             "--set", f"analysis.dt={dt:.6g}", "--set", f"analysis.end_time={steps * dt + dt / 2:.6g}",
             "--max-nodes", f"{max(2e6, 1.2 * n):.0f}", "--set", f"bodies.0.scheme.type={scheme}",
             "--set", f"bodies.0.spacing={h:.6g}", "--set", "bodies.0.scheme.linear_solver=petsc",
             "--set", "output.vtk=false", "--set", "output.every=100000"])
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))
    return proc, tag, out, (launch, processes, n, warmup)


def run(exe, outdir, launch, processes, n, steps, warmup, scheme):
    return finish(start(exe, outdir, launch, processes, n, steps, warmup, scheme))


def finish(started):
    """The measures of a run start() launched, or None when it failed."""
    proc, tag, out, (launch, processes, n, warmup) = started
    stderr = proc.communicate()[1]
    if proc.returncode != 0:
        print(f"bench_mpi: {tag} failed: {stderr.strip()[-300:]}", file=sys.stderr)
        return None
    peak_kb = float(stderr.strip().splitlines()[-1])
    s = json.load(open(os.path.join(out, "summary.json")))
    rows = list(csv.DictReader(open(os.path.join(out, "log.csv"))))
    steady = rows[warmup:] if len(rows) > warmup else rows
    scale = 1e6 / sum(float(r_["nodes"]) for r_ in steady)
    r = {"launch": launch, "processes": processes, "target": int(n), "particles": s["bodies"][0]["particles"]["final"],
         "steps": len(steady), "peak_mb": peak_kb / 1024.0,
         "us_per_particle_step": sum(float(r_["t_step"]) for r_ in steady) * scale}
    for name, col in PHASES:
        r[name] = sum(float(r_[col]) for r_ in steady) * scale
    r["rest"] = r["us_per_particle_step"] - sum(r[name] for name, _ in PHASES)
    # An MPI run's communication (process 0's log): the share of the step spent in the collectives (within the
    # phases above, waiting for the other processes included) and the MB a step received in them or sent by PETSc.
    comm = "t_comm" in rows[0] if rows else False
    r["comm_share"] = (sum(float(r_["t_comm"]) for r_ in steady) / sum(float(r_["t_step"]) for r_ in steady)
                       if comm else float("nan"))
    r["comm_mb_per_step"] = (sum(float(r_["comm_MB"]) + float(r_["petsc_MB"]) for r_ in steady) / len(steady)
                             if comm else float("nan"))
    # The point-to-point waits of PETSc's and hypre's halo exchanges (within the solver's phases).
    r["halo_share"] = (sum(float(r_["t_halo"]) for r_ in steady) / sum(float(r_["t_step"]) for r_ in steady)
                       if comm else float("nan"))
    r["per_process"] = s.get("processes", [])
    # Newton iterations a step (the steps measured) and Krylov iterations a solve (the whole run): two runs whose
    # Newton tests stop after different counts differ by whole iterations, which the speed-up per iteration removes.
    r["newton_per_step"] = sum(float(r_["iterations"]) for r_ in steady) / len(steady)
    # The monolithic scheme's Newton solver, or the fractional step's pressure solver.
    solvers = s["bodies"][0].get("linear_solvers", {})
    solver = solvers.get("newton", solvers.get("pressure", {}))
    r["krylov_per_solve"] = solver.get("iterations_per_solve", float("nan"))
    # The divided remeshing (summary.json): the ghosts over the particles, and what process 0 receives a remesh.
    divided = s["bodies"][0]["remeshing"].get("divided", {})
    r["ghost_share"] = divided.get("ghost_share", float("nan"))
    r["gathered_mb"] = divided.get("gathered_mb_per_remesh", float("nan"))
    return r


def at_once(exe, outdir, p, n, steps, warmup, scheme):
    """P serial runs of N / P particles each, started together: what P processes that each had a P-th of the work
    and nothing to exchange would take on this machine (its cores, caches and memory shared). Their mean time a step
    against the one-process run of N bounds the speed-up any division of the work among P processes reaches here."""
    started = [start(exe, outdir, "serial", 1, n / p, steps, warmup, scheme, copy=k) for k in range(p)]
    copies = [finish(s_) for s_ in started]
    if any(c is None for c in copies):
        return None
    row = {k: sum(c[k] for c in copies) / p for k in ["us_per_particle_step", "remesh", "assembly", "setup", "solve",
                                                      "rest", "newton_per_step", "krylov_per_solve"]}
    row.update({"launch": f"{p} serial at once", "processes": p, "target": int(n), "particles": copies[0]["particles"],
                "steps": copies[0]["steps"], "peak_mb": max(c["peak_mb"] for c in copies),
                "ghost_share": float("nan"), "gathered_mb": float("nan"), "comm_share": float("nan"),
                "halo_share": float("nan"),
                "comm_mb_per_step": float("nan"), "per_process": []})
    return row


def bandwidth(build, processes):
    """GB/s of one bench_bandwidth alone and of each of P copies run at once (the STREAM triad, bench_bandwidth.cpp):
    {P: [GB/s of each copy]}, or {} without the program."""
    exe = os.path.join(build, "tests", "bench_bandwidth")
    if not os.path.exists(exe):
        return {}
    out = {}
    for p in sorted({1, *processes}):
        runs = [subprocess.Popen([exe], stdout=subprocess.PIPE, text=True) for _ in range(p)]
        out[p] = [float(proc.communicate()[0].split()[0]) for proc in runs]
    return out


def bandwidth_sentence(measures):
    """The bandwidth measured before and after the runs, in words."""
    said = []
    for when, bw in measures:
        if 1 not in bw:
            continue
        one = bw[1][0]
        parts = [f"{p} at once {sum(v) / len(v):.1f} GB/s each ({sum(v) / one:.2f} times one's in all)"
                 for p, v in sorted(bw.items()) if p > 1]
        said.append(f"{when}, one process alone {one:.1f} GB/s, " + ", ".join(parts))
    if not said:
        return ""
    return (" Memory bandwidth (the STREAM triad of `tests/bench/bench_bandwidth.cpp`, in the same invocation): "
            + "; ".join(said) + ".")


def markdown(rows, commit, machine, scheme, command, bw):
    what = {"monolithic_pspg": "monolithic scheme", "fractional_step": "fractional step"}[scheme]
    lines = [f"Measured at {commit} on {machine} (`{command}`): the dam break's first steps, the "
             f"{what} with the PETSc solver, one thread per process; µs per particle-step over the steps "
             "after the first two (process 0's log), by phase; peak MB: the largest process's resident memory; the "
             "speed-up is the one-process MPI run's time per step over this run's (same size, same invocation); "
             "P serial at once: P serial runs of a P-th of the particles each, started together (the particles column "
             "gives one run's), whose speed-up (the one-process time per step over theirs) bounds what any division "
             "of the work among P processes reaches on this machine's shared cores, caches and memory; Newton: "
             "iterations a step; Krylov: iterations a linear solve (the whole run" +
             ("; the pressure solve" if scheme == "fractional_step" else "") + "); per iteration: the speed-up of the "
             "time per Newton iteration (the runs' Newton tests may stop after different counts); ghosts: "
             "the divided remeshing's ghost particles over the particles, summed over the processes; gathered MB: what "
             "process 0 receives of the others' shares of the mesh a remesh; comm: process 0's share of the step in "
             "the processes' collectives (the mesh's shares, the combined sums, the solution's gather, the decisions "
             "taken together; within the phases, waiting for the other process included) and the MB a step it "
             "received in them plus what PETSc's messages sent (the matrices' halo; hypre's are not counted); halo: "
             "process 0's share of the step in the point-to-point waits of PETSc's and hypre's halo exchanges "
             "(within the set-up and the solve, waiting for the other process included)."
             + bandwidth_sentence(bw), "",
             "| launch | processes | particles | steps | µs/particle-step | remesh | assembly | set-up | solve | rest "
             "| peak MB | speed-up | Newton | Krylov | per iteration | ghosts | gathered MB | comm | halo "
             "| comm MB a step |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['launch']} | {r['processes']} | {r['particles']} | {r['steps']} | "
                     f"{r['us_per_particle_step']:.2f} | {r['remesh']:.2f} | {r['assembly']:.2f} | {r['setup']:.2f} | "
                     f"{r['solve']:.2f} | {r['rest']:.2f} | {r['peak_mb']:.0f} | {r['speedup']:.2f} | "
                     f"{r['newton_per_step']:.2f} | {r['krylov_per_solve']:.2f} | {r['speedup_per_iteration']:.2f} | "
                     + ("– | – |" if r["ghost_share"] != r["ghost_share"] else
                        f"{100 * r['ghost_share']:.1f} % | {r['gathered_mb']:.1f} |")
                     + (" – | – | – |" if r["comm_share"] != r["comm_share"] else
                        f" {100 * r['comm_share']:.1f} % | {100 * r['halo_share']:.1f} % | "
                        f"{r['comm_mb_per_step']:.1f} |"))
    return "\n".join(lines) + "\n" + process_table(rows)


def process_table(rows):
    """Each process of the runs over several: its phases over the whole run (the first steps and the set-up of the
    first matrices included), in seconds, from summary.json's "processes"."""
    multi = [r for r in rows if len(r.get("per_process", [])) > 1]
    if not multi:
        return ""
    lines = ["", "Each process of those runs over the whole run (summary.json's `processes`), in seconds: the phases, "
             "the collectives within them (comm, waiting for the other process included), the rest of its wall time "
             "(the case's set-up, output, the steps' bookkeeping); halo: the point-to-point waits of PETSc's and "
             "hypre's halo exchanges (within the set-up and the solve); MB received in the collectives and sent by "
             "PETSc.",
             "", "| particles | process | remesh | assembly | set-up | solve | comm | halo | rest | wall | peak MB "
             "| MB received | PETSc MB sent |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in multi:
        for q in r["per_process"]:
            phases = q["remesh"] + q["assembly"] + q["factorization"] + q["solve"]
            lines.append(f"| {r['particles']} | {q['rank']} | {q['remesh']:.2f} | {q['assembly']:.2f} | "
                         f"{q['factorization']:.2f} | {q['solve']:.2f} | {q['comm']:.2f} | {q['halo']:.2f} | "
                         f"{q['wall'] - phases:.2f} | "
                         f"{q['wall']:.2f} | {q['peak_MB']:.0f} | {q['comm_MB']:.0f} | {q['petsc_MB']:.0f} |")
    return "\n".join(lines) + "\n"


def head_commit():
    return subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True,
                          text=True).stdout.strip()


def rewrite(doc, marker, table):
    """Puts `table` between the markers <!-- MARKER begin --> and <!-- MARKER end --> of `doc`."""
    text = open(doc).read()
    begin, end = f"<!-- {marker} begin -->", f"<!-- {marker} end -->"
    if begin not in text or end not in text:
        sys.exit(f"bench_mpi: {doc} has no {begin} ... {end} markers")
    head, rest = text.split(begin, 1)
    open(doc, "w").write(head + begin + "\n" + table + end + rest.split(end, 1)[1])


def publish(rows, doc, marker, scheme, command, bw):
    table = markdown(rows, head_commit(), f"{os.cpu_count()} cores, {platform.machine()}", scheme, command, bw)
    print(table)
    if doc:
        rewrite(doc, marker, table)


def seconds_per_step(r):
    return r["us_per_particle_step"] * r["particles"] / 1e6


def weak(a, exe, outdir):
    """Weak scaling: the one-process MPI run at N particles against P processes at P N (the same particles per
    process); the efficiency is the one-process time per step (or per Newton iteration) over the P-process one."""
    bw_before = bandwidth(a.build, a.processes)
    rows = []
    for n in a.weak:
        pair = [run(exe, outdir, "mpirun", 1, n, a.steps, a.warmup, a.scheme)]
        pair += [run(exe, outdir, "mpirun", p, p * n, a.steps, a.warmup, a.scheme) for p in a.processes]
        if not a.no_bound:  # P serial runs of N at once: the efficiency of P processes that exchange nothing
            pair += [at_once(exe, outdir, p, p * n, a.steps, a.warmup, a.scheme) for p in a.processes]
        pair = [r for r in pair if r]
        base = next((r for r in pair if r["processes"] == 1), None)
        for r in pair:
            # The P serial runs at once: each copy's time a step (its work is the one-process run's).
            r["efficiency"] = seconds_per_step(base) / seconds_per_step(r) if base else float("nan")
            r["efficiency_per_iteration"] = (r["efficiency"] * r["newton_per_step"] / base["newton_per_step"] if base
                                             else float("nan"))
            print(f"bench_mpi: weak np {r['processes']} n {r['particles']}: {seconds_per_step(r):.3f} s a step, "
                  f"efficiency {r['efficiency']:.2f}", file=sys.stderr)
        rows += pair
    bw = [("before the runs", bw_before), ("after them", bandwidth(a.build, a.processes))]
    command = "tests/bench/bench_mpi.py --weak " + " ".join(("%g" % n).replace("e+0", "e") for n in a.weak)
    lines = [f"Measured at {head_commit()} on {os.cpu_count()} cores, {platform.machine()} (`{command}`): the same particles "
             "per process, the dam break's first steps as in the table above; seconds a step over the steps after "
             "the first two (process 0's log); efficiency: the one-process time a step (or a Newton iteration) over "
             "this run's, 1 when the work per process stays the same (P serial at once: P serial runs of N particles "
             "started together, each copy's time a step: the efficiency P processes that exchange nothing reach on "
             "this machine); comm: process 0's share of the step in the processes' collectives, as in the table "
             "above, and halo its share in the halo exchanges' waits." + bandwidth_sentence(bw), "",
             "| processes | particles | s a step | Newton a step | remesh | assembly | set-up | solve (µs/particle-step) "
             "| efficiency | per iteration | ghosts | comm | halo |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        who = f"{r['processes']}" if r["launch"] == "mpirun" else r["launch"]
        lines.append(f"| {who} | {r['particles']} | {seconds_per_step(r):.3f} | {r['newton_per_step']:.2f} | "
                     f"{r['remesh']:.2f} | {r['assembly']:.2f} | {r['setup']:.2f} | {r['solve']:.2f} | "
                     f"{r['efficiency']:.2f} | {r['efficiency_per_iteration']:.2f} | "
                     + ("– |" if r["ghost_share"] != r["ghost_share"] else f"{100 * r['ghost_share']:.1f} % |")
                     + (" – | – |" if r["comm_share"] != r["comm_share"] else
                        f" {100 * r['comm_share']:.1f} % | {100 * r['halo_share']:.1f} % |"))
    table = "\n".join(lines) + "\n"
    print(table)
    if a.doc:
        rewrite(a.doc, a.marker if a.marker != "bench_mpi" else "bench_mpi_weak", table)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--sizes", nargs="+", type=float, default=[1e5, 1e6])
    ap.add_argument("--processes", nargs="+", type=int, default=[2])
    ap.add_argument("--steps", type=int, default=8)
    ap.add_argument("--warmup", type=int, default=2)
    ap.add_argument("--scheme", default="monolithic_pspg", choices=["monolithic_pspg", "fractional_step"])
    ap.add_argument("--doc")
    ap.add_argument("--marker", default="bench_mpi")
    ap.add_argument("--no-bound", action="store_true",
                    help="leave out the P serial runs of N / P particles at once (the bound on the speed-up)")
    ap.add_argument("--weak", nargs="+", type=float,
                    help="weak scaling instead: one process at each N against P processes at P N")
    a = ap.parse_args()
    exe = os.path.join(a.build, "lagfsi")
    outdir = a.outdir or os.path.join(a.build, "bench_mpi")
    os.makedirs(outdir, exist_ok=True)
    if a.weak:
        weak(a, exe, outdir)
        return
    rows = []
    bw_before = bandwidth(a.build, a.processes)
    for n in a.sizes:
        size_rows = [run(exe, outdir, "serial", 1, n, a.steps, a.warmup, a.scheme),
                     run(exe, outdir, "mpirun", 1, n, a.steps, a.warmup, a.scheme)]
        size_rows += [run(exe, outdir, "mpirun", p, n, a.steps, a.warmup, a.scheme) for p in a.processes]
        if not a.no_bound:
            size_rows += [at_once(exe, outdir, p, n, a.steps, a.warmup, a.scheme) for p in a.processes]
        size_rows = [r for r in size_rows if r]
        base = next((r for r in size_rows if r["launch"] == "mpirun" and r["processes"] == 1), None)
        for r in size_rows:
            # Per step (the runs of N particles have the same mesh at every step; the copies at once a P-th of it).
            r["speedup"] = seconds_per_step(base) / seconds_per_step(r) if base else float("nan")
            r["speedup_per_iteration"] = (r["speedup"] * r["newton_per_step"] / base["newton_per_step"] if base
                                          else float("nan"))
            print(f"bench_mpi: {r['launch']} np {r['processes']} n {r['particles']}: "
                  f"{r['us_per_particle_step']:.2f} us/particle-step, speed-up {r['speedup']:.2f}", file=sys.stderr)
        rows += size_rows
    with open(os.path.join(outdir, "bench_mpi.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    command = "tests/bench/bench_mpi.py --sizes " + " ".join(("%g" % n).replace("e+0", "e") for n in a.sizes)
    if a.scheme != "monolithic_pspg":
        command += " --scheme " + a.scheme
    bw = [("before the runs", bw_before), ("after them", bandwidth(a.build, a.processes))]
    print("bench_mpi:" + bandwidth_sentence(bw), file=sys.stderr)
    publish(rows, a.doc, a.marker, a.scheme, command, bw)


if __name__ == "__main__":
    main()
