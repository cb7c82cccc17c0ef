#!/usr/bin/python3
"""Benchmark (not a test): how the cost of a PFEM step grows with the particle count, direct against Krylov.

Runs `lagfsi run cases/dam_break_tank/case.json` with a finer spacing h = 0.0073 sqrt(861 / N) for each target
particle count N (the same tank and water column) and the time step scaled with h (dt = 1 ms h / 0.0073: the same
Courant number, so that a step asks the same of the Newton iterations at every size); a few steps from rest, a
per-step cost measurement, not a flow result; for each scheme (monolithic_pspg, fractional_step) and each linear solver
(the direct one: klu / cholmod; petsc: FGMRES + Schur field split / CG + BoomerAMG), on the given thread
counts. Per run it reads log.csv and summary.json and reports the particles, steps, microseconds per
particle-step in all and by phase (remesh, assembly, solver set-up, solve, rest) over the steps after the first
`--warmup` ones (the first steps of a large run pay for touching its memory the first time, and start from rest), the Krylov iterations per solve (mean, largest),
and the peak memory (/usr/bin/time). The floor at each size is one remesh plus one Poisson solve with
CG + BoomerAMG per particle-step: the remesh and pressure-solver times of the fractional step's Krylov run at
that size.

usage: /usr/bin/python3 tests/bench/bench_scaling.py [OUTDIR] [--build DIR] [--sizes 1e3 1e4 1e5]
           [--schemes monolithic_pspg fractional_step] [--solvers direct petsc] [--threads 1 2]
           [--direct-max 1.2e5] [--steps 12] [--warmup 3] [--doc docs/solvers.md]
--direct-max: no direct run above this many particles (KLU at 1e5 particles takes ~20 s a step).
--doc: rewrite the table between the markers <!-- bench_scaling begin --> and <!-- bench_scaling end --> of that
file, with the commit and the machine; --from-csv FILE: the rows of an earlier run's bench_scaling.csv, not new
runs (the commit is then given with --commit).
OUTDIR (default BUILD/bench_scaling/) receives bench_scaling.csv and the runs' output folders.
"""
import argparse
import csv
import json
import os
import platform
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(REPO, "cases", "dam_break_tank", "case.json")
H0, N0, DT = 0.0073, 861, 1e-3
DIRECT = {"monolithic_pspg": "klu", "fractional_step": "cholmod"}
COLUMNS = ["scheme", "solver", "threads", "target", "particles", "steps", "us_per_particle_step", "remesh",
           "assembly", "setup", "solve", "rest", "solves_per_step", "iterations_mean", "iterations_max", "peak_mb",
           "floor",
           "ratio_to_floor", "method"]


def run(exe, outdir, scheme, solver, threads, n, steps, warmup):
    h = H0 * (N0 / n) ** 0.5
    dt = DT * h / H0
    tag = f"{scheme}_{solver}_t{threads}_n{int(n)}"
    out = os.path.join(outdir, tag)
    ls = DIRECT[scheme] if solver == "direct" else solver
    args = ["/usr/bin/time", "-f", "%M", exe, "run", CASE, "-o", out, "--quiet", "--threads", str(threads),
            "--set", f"analysis.dt={dt:.6g}", "--set", f"analysis.end_time={steps * dt + dt / 2:.6g}",
            "--set", f"bodies.0.spacing={h:.6g}",
            "--set", f"bodies.0.scheme.type={scheme}", "--set", f"bodies.0.scheme.linear_solver={ls}",
            "--set", "output.vtk=false", "--set", "output.every=100000"]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        print(f"bench_scaling: {tag} failed: {p.stderr.strip()}", file=sys.stderr)
        return None
    peak_kb = float(p.stderr.strip().splitlines()[-1])
    s = json.load(open(os.path.join(out, "summary.json")))
    b = s["bodies"][0]
    rows = list(csv.DictReader(open(os.path.join(out, "log.csv"))))
    nsteps = len(rows)
    steady = rows[warmup:] if nsteps > warmup else rows
    particles = b["particles"]["final"]
    scale = 1e6 / sum(float(r_["nodes"]) for r_ in steady)  # per particle-step over the steady steps

    def phase(col):
        return sum(float(r_[col]) for r_ in steady) * scale

    solvers = b["linear_solvers"]
    main = solvers.get("newton", solvers.get("pressure"))
    total = phase("t_step")
    # log.csv's factorization and solve columns are the linear solvers' set-up and solve.
    r = {"scheme": scheme, "solver": solver, "threads": threads, "target": int(n), "particles": particles,
         "steps": len(steady), "us_per_particle_step": total, "remesh": phase("t_remesh"),
         "assembly": phase("t_assembly"), "setup": phase("t_factorization"), "solve": phase("t_solve"),
         "rest": total - phase("t_remesh") - phase("t_assembly") - phase("t_factorization") - phase("t_solve"),
         "solves_per_step": main["solves"] / nsteps, "iterations_mean": main.get("iterations_per_solve", 0.0),
         "iterations_max": main.get("iterations_max", 0),
         "peak_mb": peak_kb / 1024.0, "method": main["method"]}
    if scheme == "fractional_step" and solver == "petsc":
        # The floor: the remesh and the Poisson's set-up and solve (the viscous predictor's share taken out).
        p_, v_ = solvers["pressure"], solvers.get("viscous", {})
        share = (p_["setup_seconds"] + p_["solve_seconds"]) / max(
            1e-300, p_["setup_seconds"] + p_["solve_seconds"] + v_.get("setup_seconds", 0) + v_.get("solve_seconds", 0))
        r["floor_value"] = r["remesh"] + share * (r["setup"] + r["solve"])
    return r


def markdown(rows, commit, machine):
    lines = [f"Measured at {commit} on {machine} (`tests/bench/bench_scaling.py`). µs per particle-step over the "
             "steps after the first three (the steps column counts those); "
             "phases: remesh, assembly, solver set-up, solve; linear solves per step (the Newton iterations of the "
             "monolithic scheme); Krylov iterations per solve (mean / largest); "
             "the floor is one remesh + one CG + BoomerAMG Poisson solve at the same size.", "",
             "| scheme | solver | threads | particles | steps | µs/particle-step | remesh | assembly | set-up | solve "
             "| solves/step | iterations | peak MB | × floor |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        it = f"{r['iterations_mean']:.1f} / {r['iterations_max']}" if r["iterations_max"] else "direct"
        ratio = f"{r['ratio_to_floor']:.1f}" if r.get("ratio_to_floor") else ""
        lines.append(f"| {r['scheme']} | {r['method']} | {r['threads']} | {r['particles']} | {r['steps']} | "
                     f"{r['us_per_particle_step']:.1f} | {r['remesh']:.1f} | {r['assembly']:.1f} | {r['setup']:.1f} | "
                     f"{r['solve']:.1f} | {r['solves_per_step']:.1f} | {it} | {r['peak_mb']:.0f} | {ratio} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--sizes", nargs="+", type=float, default=[1e3, 1e4, 1e5])
    ap.add_argument("--schemes", nargs="+", default=["monolithic_pspg", "fractional_step"])
    ap.add_argument("--solvers", nargs="+", default=["direct", "petsc"])
    ap.add_argument("--threads", nargs="+", type=int, default=[1])
    ap.add_argument("--direct-max", type=float, default=1.2e5)
    ap.add_argument("--steps", type=int, default=12)
    ap.add_argument("--warmup", type=int, default=3)
    ap.add_argument("--doc")
    ap.add_argument("--from-csv")
    ap.add_argument("--commit")
    a = ap.parse_args()
    if a.from_csv:
        rows = []
        for r in csv.DictReader(open(a.from_csv)):
            for k in COLUMNS:
                if k not in ("scheme", "solver", "method"):
                    r[k] = float(r[k]) if "." in r[k] or "e" in r[k] else int(r[k]) if r[k] else 0
            rows.append(r)
        publish(rows, a.commit, a.doc)
        return
    exe = os.path.join(a.build, "lagfsi")
    outdir = a.outdir or os.path.join(a.build, "bench_scaling")
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for n in a.sizes:
        floor = None
        # The fractional step's Krylov run first: it gives the floor of this size.
        order = sorted(((s, v) for s in a.schemes for v in a.solvers),
                       key=lambda sv: (sv[0] != "fractional_step" or sv[1] != "petsc"))
        size_rows = []
        for threads in a.threads:
            for scheme, solver in order:
                if solver == "direct" and n > a.direct_max:
                    continue
                r = run(exe, outdir, scheme, solver, threads, n, a.steps, a.warmup)
                if r is None:
                    continue
                if "floor_value" in r and floor is None:
                    floor = r.pop("floor_value")
                r.pop("floor_value", None)
                size_rows.append(r)
                print(f"{scheme:16s} {r['method']:18s} t{threads} N={r['particles']:8d} "
                      f"{r['us_per_particle_step']:7.1f} us/particle-step, it {r['iterations_mean']:.1f}, "
                      f"{r['peak_mb']:.0f} MB", flush=True)
        for r in size_rows:
            r["floor"] = floor or 0.0
            r["ratio_to_floor"] = r["us_per_particle_step"] / floor if floor else 0.0
        rows += size_rows
    with open(os.path.join(outdir, "bench_scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in COLUMNS})
    publish(rows, None, a.doc)


def publish(rows, commit, doc):
    """Prints the table and, with `doc`, writes it between that file's markers."""
    commit = commit or subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True,
                                      text=True).stdout.strip()
    machine = f"{os.cpu_count()} cores, {platform.processor() or platform.machine()}"
    table = markdown(rows, commit, machine)
    print(table)
    if doc:
        text = open(doc).read()
        b, e = "<!-- bench_scaling begin -->\n", "<!-- bench_scaling end -->"
        i, j = text.index(b) + len(b), text.index(e)
        open(doc, "w").write(text[:i] + table + text[j:])


if __name__ == "__main__":
    main()
