#!/usr/bin/python3
"""Benchmark (not a test): MPM particle-updates per second (one particle through one full explicit sub-step:
particles to grid, grid update, grid to particles, MUSL re-map and stress update) for an elastic block of about
100 000 particles settling under gravity, with linear and GIMP shape functions, on 1 and 2 threads, measured in
one invocation. The target: at least 5 million particle-updates per second with linear shape functions on
2 threads.

usage: /usr/bin/python3 tests/bench/bench_mpm.py [OUTDIR] [--build DIR] [--steps 20]
"""
import argparse
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def case(shape, steps):
    # Block 7.5 m x 2 m in a 10 m x 3 m grid of 2.5 cm cells, 2 x 2 particles per cell: 96 000 particles.
    return {
        "name": "bench_mpm",
        "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": steps * 1e-3},
        "gravity": [0.0, -9.81],
        "bodies": [{
            "name": "block", "type": "mpm",
            "material": {"type": "linear_elastic", "young": 1.0e7, "poisson": 0.3, "density": 2000.0},
            "grid": {"origin": [0, 0], "size": [10.0, 3.0], "cell": 0.025},
            "regions": [{"type": "rectangle", "origin": [1.25, 0], "size": [7.5, 2.0]}],
            "particles_per_cell": 2, "shape_functions": shape, "update": "musl", "cfl": 0.5,
            "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [10, 0]}}],
        }],
        "output": {"vtk": False},
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--steps", type=int, default=20)
    a = ap.parse_args()
    exe = os.path.join(a.build, "lagfsi")
    if not os.access(exe, os.X_OK):
        sys.exit(f"bench_mpm: {exe} not found (build first)")
    out = a.outdir or os.path.join(a.build, "bench_mpm")
    os.makedirs(out, exist_ok=True)
    print("shape   threads  particles  sub-steps  wall[s]  M particle-updates/s")
    for shape in ("linear", "gimp"):
        path = os.path.join(out, f"{shape}.json")
        with open(path, "w") as f:
            json.dump(case(shape, a.steps), f)
        for threads in (1, 2):
            run_out = os.path.join(out, f"{shape}_{threads}")
            subprocess.run([exe, "run", path, "-o", run_out, "--quiet", "--threads", str(threads)], check=True)
            with open(os.path.join(run_out, "summary.json")) as f:
                s = json.load(f)
            n = s["bodies"][0]["nodes"]            # particles
            k = s["newton_iterations"]["total"]    # sub-steps
            t = s["timing"]["assembly"]            # the MPM step's time (output excluded)
            print(f"{shape:7s} {threads:7d} {n:10d} {k:10d} {t:8.2f} {n * k / t / 1e6:12.2f}")


if __name__ == "__main__":
    main()
