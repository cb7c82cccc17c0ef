#!/usr/bin/python3
"""Benchmark (not a test): cost of one PFEM step of the dam break (cases/dam_break_tank) against the
practical floor of a step (bench_pfem_floor: remesh + CHOLMOD factorization/solve of a P1 Laplacian).

Runs `lagfsi run cases/dam_break_tank/case.json` at h = L/20, L/40, L/80 (dt = 1, 0.5, 0.25 ms; 0.1 s of
flow at L/20 and L/40, 0.02 s at L/80 (80 steps: one L/80 step takes ~1.5 s, 0.05 s of flow would take
~6 min per run); a per-step cost measurement, not a flow result) with --threads 1
and 2, reads each run's log.csv and reports per run: mean particles, steps, mean Newton iterations, and
the wall time per particle per step (sum over steps of the phase time / sum over steps of the particle
count), split into remeshing (triangulation, alpha test, particle removal and insertion), assembly (with the
sparsity pattern), factorization, solve, output and the rest of the step (other = t_step - the five phases); then the floor
per particle at the same h (bench_pfem_floor, single thread, on the initial cloud; the floor per particle
varies slowly with the particle count, so it is compared per particle with the run's mean count) and the
ratio whole step / floor.

usage: /usr/bin/python3 tests/bench/bench_pfem.py [OUTDIR] [--build DIR] [--threads 1 2] [--levels 20 40 80]
                                                [--time-scale 1.0] [--omp-wait-policy active|passive]
Columns run_wall_s / run_cpu_s: cpu well below wall with --threads 1 means the machine was shared (the
per-phase times are then inflated).
OUTDIR (default BUILD/bench_pfem/) receives bench_pfem.csv, floor.csv and the runs' output folders.
"""
import argparse
import csv
import io
import os
import resource
import subprocess
import sys
import time

L = 0.146
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(REPO, "cases", "dam_break_tank", "case.json")


def find_exe(build, name):
    for cand in (os.path.join(build, name), os.path.join(build, "tests", name),
                 os.path.join(build, "tests", "bench", name), os.path.join(build, "bin", name)):
        if os.path.isfile(cand) and os.access(cand, os.X_OK):
            return cand
    for root, _, files in os.walk(build):
        if name in files and os.access(os.path.join(root, name), os.X_OK):
            return os.path.join(root, name)
    sys.exit(f"bench_pfem: {name} not found under {build} (build it: cmake --build {build} --target {name})")


def run_floor(exe, levels, repeats):
    args = [exe, "--csv", "--repeats", str(repeats)] + [f"L/{k}" for k in levels]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    return {k: r for k, r in zip(levels, rows)}, out


def read_log(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise RuntimeError(f"{path}: no steps")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=None, help="output folder (default BUILD/bench_pfem)")
    ap.add_argument("--build", default=os.path.join(REPO, "build-bench"))
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--levels", type=int, nargs="+", default=[20, 40, 80], help="L/h values")
    ap.add_argument("--schemes", nargs="+", default=["monolithic_pspg", "fractional_step"],
                    choices=["monolithic_pspg", "fractional_step"])
    ap.add_argument("--time-scale", type=float, default=1.0, help="multiply the simulated times")
    ap.add_argument("--floor-repeats", type=int, default=5)
    ap.add_argument("--omp-wait-policy", choices=["active", "passive"], default=None,
                    help="OMP_WAIT_POLICY for the lagfsi runs (default: inherited). On a loaded machine the "
                         "default spinning makes --threads 2 several times slower; passive avoids that")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    out = os.path.abspath(a.out or os.path.join(build, "bench_pfem"))
    os.makedirs(out, exist_ok=True)
    lagfsi = find_exe(build, "lagfsi")
    floor_exe = find_exe(build, "bench_pfem_floor")

    t_start = time.time()
    load0 = os.getloadavg()
    floor, floor_csv = run_floor(floor_exe, a.levels, a.floor_repeats)
    with open(os.path.join(out, "floor.csv"), "w") as f:
        f.write(floor_csv)

    results = []
    for k in a.levels:
        h = L / k
        dt = 1e-3 * 20.0 / k
        end = (0.1 if k <= 40 else 0.02) * a.time_scale
        for scheme, th in ((s, t) for s in a.schemes for t in a.threads):
            run_dir = os.path.join(out, f"run_{scheme}_L{k}_t{th}")
            cmd = [lagfsi, "run", CASE, "-o", run_dir, "--quiet", "--threads", str(th),
                   "--set", f"bodies.0.spacing={h!r}", "--set", f"analysis.dt={dt!r}",
                   "--set", f"analysis.end_time={end!r}", "--set", f"bodies.0.scheme.type={scheme}"]
            t0 = time.time()
            ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            env = dict(os.environ)
            if a.omp_wait_policy:
                env["OMP_WAIT_POLICY"] = a.omp_wait_policy
            p = subprocess.run(cmd, capture_output=True, text=True, env=env)
            wall = time.time() - t0
            ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)
            if p.returncode != 0:
                print(f"bench_pfem: {scheme} L/{k} threads {th}: exit {p.returncode}: {p.stderr.strip()}", file=sys.stderr)
            rows = read_log(os.path.join(run_dir, "log.csv"))
            n = [float(r["nodes"]) for r in rows]
            sn = sum(n)

            def per_part(col):
                return 1e6 * sum(float(r[col]) for r in rows) / sn

            rem, asm, fac, sol, outp, step = (per_part(c) for c in ("t_remesh", "t_assembly", "t_factorization",
                                                                    "t_solve", "t_output", "t_step"))
            fl = float(floor[k]["floor_us"])
            results.append({
                "scheme": scheme, "L_over_h": k, "h": f"{h:.6g}", "dt": f"{dt:.6g}", "end_time": f"{end:.6g}", "threads": th,
                "steps": len(rows), "mean_particles": f"{sn / len(rows):.1f}",
                "mean_elements": f"{sum(float(r['elements']) for r in rows) / len(rows):.1f}",
                "mean_iterations": f"{sum(float(r['iterations']) for r in rows) / len(rows):.3f}",
                "remesh_us": f"{rem:.3f}", "assembly_us": f"{asm:.3f}", "factorization_us": f"{fac:.3f}",
                "solve_us": f"{sol:.3f}", "output_us": f"{outp:.3f}",
                "other_us": f"{step - rem - asm - fac - sol - outp:.3f}",
                "step_us": f"{step:.3f}", "floor_particles": floor[k]["particles"],
                "floor_remesh_us": floor[k]["remesh_us"], "floor_chol_us": floor[k]["chol_us"],
                "floor_us": f"{fl:.3f}", "step_over_floor": f"{step / fl:.2f}",
                "run_wall_s": f"{wall:.2f}", "run_cpu_s": f"{cpu:.2f}", "exit_code": p.returncode,
            })
            print(f"  {scheme} L/{k} threads {th}: {len(rows)} steps, wall {wall:.1f} s, cpu {cpu:.1f} s "
                  f"(load {os.getloadavg()[0]:.1f})", flush=True)

    cols = list(results[0].keys())
    with open(os.path.join(out, "bench_pfem.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(results)

    total = time.time() - t_start
    print(f"bench_pfem: dam break, times in us per particle per step (floor: bench_pfem_floor, 1 thread, "
          f"best of {a.floor_repeats}); load average before: {load0[0]:.2f}; "
          f"OMP_WAIT_POLICY={a.omp_wait_policy or os.environ.get('OMP_WAIT_POLICY', '(unset)')}")
    hdr = ("scheme", "L/h", "thr", "dt[ms]", "steps", "particles", "iter", "remesh", "assembly", "factor", "solve",
           "output", "other", "step", "floor", "step/floor", "wall[s]", "cpu[s]")
    print("%-15s %5s %4s %7s %6s %10s %6s | %8s %8s %8s %8s %8s %8s %8s | %8s %10s | %7s %7s" % hdr)
    for r in results:
        print("%-15s %5d %4d %7.3f %6d %10s %6s | %8s %8s %8s %8s %8s %8s %8s | %8s %10s | %7s %7s" % (
            r["scheme"], r["L_over_h"], r["threads"], 1e3 * float(r["dt"]), r["steps"], r["mean_particles"],
            r["mean_iterations"][:5], r["remesh_us"], r["assembly_us"], r["factorization_us"], r["solve_us"],
            r["output_us"], r["other_us"], r["step_us"], r["floor_us"], r["step_over_floor"], r["run_wall_s"], r["run_cpu_s"]))
    print(f"floor (bench_pfem_floor --csv):\n{floor_csv.rstrip()}")
    print(f"total benchmark time {total:.1f} s; load average after: {os.getloadavg()[0]:.2f}; written to {out}")


if __name__ == "__main__":
    main()
