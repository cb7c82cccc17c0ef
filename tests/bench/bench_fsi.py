#!/usr/bin/python3
"""Benchmark (not a test): what a coupled step costs against a fluid step, on the elastic obstacle of
cases/elastic_obstacle_walhorn (fractional-step fluid, IQN-ILS).

Two runs of the same flow with --threads 1, measured in this one invocation:
  coupled: the case as it is (the obstacle an elastic solid, coupled through ghost particles);
  rigid:   the same fluid with the obstacle as part of the tank's wall polyline (no solid, no coupling).
For the window [T0, T1] (default 0.15-0.45 s: impact and first swing, every step coupled) it reports the mean
wall time per step of each run, their ratio, and the mean FSI iterations per coupled step k of the coupled
run; the target is ratio <= k + 1 (each coupling pass re-solves the fluid step, whose matrices are
factorized once per step and reused, and the solid). Also the split of the coupled step by phase.

usage: /usr/bin/python3 tests/bench/bench_fsi.py [OUTDIR] [--build DIR] [--t0 0.15] [--t1 0.45] [--set KEY=VALUE]...
--set adds an override to both runs, e.g. --set bodies.0.scheme.linear_solver=petsc (the Krylov solvers, whose
preconditioner a coupling pass reuses as a direct solver reuses its factorization).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(REPO, "cases", "elastic_obstacle_walhorn", "case.json")


def run(exe, out, sets):
    args = [exe, "run", CASE, "-o", out, "--quiet", "--threads", "1", "--set", "output.vtk=false"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True)
    with open(os.path.join(out, "log.csv")) as f:
        return list(csv.DictReader(f))


def window(rows, t0, t1, key):
    vals = [float(r[key]) for r in rows if t0 <= float(r["time"]) <= t1]
    return sum(vals) / len(vals) if vals else float("nan"), len(vals)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--t0", type=float, default=0.15)
    ap.add_argument("--t1", type=float, default=0.45)
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    exe = os.path.join(a.build, "lagfsi")
    if not os.access(exe, os.X_OK):
        sys.exit(f"bench_fsi: {exe} not found (build first)")
    out = a.outdir or os.path.join(a.build, "bench_fsi")
    os.makedirs(out, exist_ok=True)
    end = "analysis.end_time=%g" % a.t1
    coupled = run(exe, os.path.join(out, "coupled"), [end] + a.set)
    # The rigid variant: the obstacle's outline joins the tank's wall; the solid body, the coupling and the
    # probes on them go.
    walls = ('bodies.0.walls=[{"name": "tank", "points": [[0, 0.584], [0, 0], [0.292, 0], [0.292, 0.08], '
             '[0.304, 0.08], [0.304, 0], [0.584, 0], [0.584, 0.584]]}]')
    with open(CASE) as f:
        text = "\n".join(line for line in f if not line.lstrip().startswith("//"))
    water = json.loads(text)["bodies"][0]
    rigid = run(exe, os.path.join(out, "rigid"),
                [end, "bodies=[%s]" % json.dumps(water), walls, "couplings=[]",
                 'probes=[{"name": "front_x", "type": "front", "body": "water", "floor": 0.0}]'] + a.set)
    tc, n = window(coupled, a.t0, a.t1, "t_step")
    tr, _ = window(rigid, a.t0, a.t1, "t_step")
    k, _ = window(coupled, a.t0, a.t1, "fsi_iterations")
    nc, _ = window(coupled, a.t0, a.t1, "nodes")
    nr, _ = window(rigid, a.t0, a.t1, "nodes")
    print("window %.2f-%.2f s, %d steps" % (a.t0, a.t1, n))
    print("rigid obstacle : %.2f ms per step (%.0f particles)" % (1e3 * tr, nr))
    print("elastic, coupled: %.2f ms per step (%.0f particles and solid nodes), %.2f FSI iterations per step" %
          (1e3 * tc, nc, k))
    print("ratio coupled / rigid = %.2f   (goal <= iterations + 1 = %.2f)" % (tc / tr, k + 1))
    for ph in ("t_remesh", "t_assembly", "t_factorization", "t_solve"):
        m, _ = window(coupled, a.t0, a.t1, ph)
        print("  coupled %-16s %.2f ms" % (ph, 1e3 * m))


if __name__ == "__main__":
    main()
