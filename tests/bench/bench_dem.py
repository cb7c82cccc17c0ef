#!/usr/bin/python3
"""Benchmark (not a test): the same 2D granular bed in lagfsi's DEM body and in LAMMPS, particle-steps per second.

The bed: about 27 000 discs (d = 2 mm, rho = 2500 kg/m^3, unit depth), 180 per row and 150 rows on a
hexagonal lattice with a 2 % gap and a small random jitter, in a box (floor and two side walls), settling under
gravity for 2000 steps of 2e-5 s. Contact law in both codes: linear spring-dashpot with a Coulomb tangential
spring with history (LAMMPS pair gran/hooke/history: Kn = 1e5 N/m, Kt = 2/7 Kn, gamma_n = 50 1/s,
gamma_t = 25 1/s (damping force m_eff gamma v), mu = 0.5; lagfsi "law": "linear", "damping": "viscous" with the
same numbers), rotation on (LAMMPS fix nve/sphere disc: I = m r^2/2), fix enforce2d, neighbour skin 0.5 mm
checked every step. The bench writes both inputs, runs lagfsi with 1 and 2 OpenMP threads and LAMMPS with 1 and
2 MPI ranks (mpirun), one after the other, and prints particle-steps per second (discs x steps / loop time:
LAMMPS "Loop time", lagfsi the DEM body's wall time from summary.json) and the ratios.

usage: /usr/bin/python3 tests/bench/bench_dem.py [OUTDIR] [--build DIR] [--steps 2000] [--rows 150] [--cols 180]
       [--only lagfsi|lammps] [--threads 1,2]
"""
import argparse
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

D = 2e-3            # diameter [m]
R = D / 2
RHO = 2500.0
KN = 1e5
KT = KN * 2.0 / 7.0
GN = 50.0           # gamma_n [1/s]
GT = 25.0
MU = 0.5
DT = 2e-5
SKIN = 0.5e-3


def bed(rows, cols, seed=1):
    """Disc centres: hexagonal lattice, pitch 1.02 d, jitter 0.5 % d; and the box width."""
    rng = random.Random(seed)
    pitch = 1.02 * D
    dy = pitch * math.sqrt(3) / 2
    pts = []
    for j in range(rows):
        for i in range(cols - (j % 2)):
            x = R + 0.01 * D + i * pitch + (0.5 * pitch if j % 2 else 0.0) + rng.uniform(-0.005, 0.005) * D
            y = R + 0.01 * D + j * dy + rng.uniform(-0.005, 0.005) * D
            pts.append((x, y))
    width = cols * pitch + 0.02 * D
    height = rows * dy + 2 * D
    return pts, width, height


def write_lagfsi(path, pts, width, height, steps):
    case = {
        "name": "bench_dem",
        "analysis": {"type": "dynamic", "dt": DT * 100, "end_time": DT * steps},
        "gravity": [0.0, -9.81],
        "bodies": [{
            "name": "bed", "type": "dem",
            "material": {"density": RHO},
            "contact": {"law": "linear", "kn": KN, "damping": "viscous", "gamma_n": GN, "kt_ratio": KT / KN,
                        "gamma_t": GT, "friction": MU, "tangential": "coulomb"},
            "discs": [{"type": "list", "discs": [[x, y, R] for x, y in pts]}],
            "walls": [{"name": "box", "points": [[0.0, height * 3], [0.0, 0.0], [width, 0.0], [width, height * 3]]}],
            "time_step": {"dt": DT},
            "neighbour": {"skin": SKIN},
        }],
        "output": {"vtk": False},
    }
    with open(path, "w") as f:
        json.dump(case, f)


def write_lammps(folder, pts, width, height, steps):
    mass = RHO * math.pi * R * R
    with open(os.path.join(folder, "bed.data"), "w") as f:
        f.write("bench_dem bed\n\n%d atoms\n1 atom types\n\n" % len(pts))
        f.write("%.9g %.9g xlo xhi\n%.9g %.9g ylo yhi\n-0.001 0.001 zlo zhi\n\nAtoms # sphere\n\n"
                % (-0.5 * D, width + 0.5 * D, -0.5 * D, height * 3))
        # atom-ID atom-type diameter density x y z; density set so that mass = rho pi r^2 (overridden below)
        for k, (x, y) in enumerate(pts):
            f.write("%d 1 %.9g %.9g %.12g %.12g 0\n" % (k + 1, D, RHO, x, y))
    with open(os.path.join(folder, "in.bench"), "w") as f:
        f.write(f"""# written by tests/bench/bench_dem.py
units si
dimension 2
atom_style sphere
boundary f f p
comm_modify vel yes
read_data bed.data
set group all mass {mass:.12g}
neighbor {SKIN} bin
neigh_modify delay 0 every 1 check yes
pair_style gran/hooke/history {KN} {KT} {GN} {GT} {MU} 1
pair_coeff * *
fix grav all gravity 9.81 vector 0 -1 0
fix int all nve/sphere disc
fix floor all wall/gran hooke/history {KN} {KT} {GN} {GT} {MU} 1 yplane 0.0 NULL
fix sides all wall/gran hooke/history {KN} {KT} {GN} {GT} {MU} 1 xplane 0.0 {width:.12g}
fix 2d all enforce2d
timestep {DT}
thermo 1000
run {steps}
""")


def run_lagfsi(exe, case, out, threads):
    subprocess.run([exe, "run", case, "-o", out, "--quiet", "--threads", str(threads)], check=True)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    b = s["bodies"][0]
    return b["nodes"], b["substeps"], b["wall_time"], s["wall_time"]


def run_lammps(folder, ranks):
    lmp = shutil.which("lmp") or shutil.which("lmp_serial")
    if not lmp:
        sys.exit("bench_dem: LAMMPS not found (apt-get install -y --no-install-recommends lammps)")
    cmd = [lmp, "-in", "in.bench", "-log", f"log.{ranks}", "-screen", "none"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.time()
    subprocess.run(cmd, cwd=folder, check=True, env=env)
    whole = time.time() - t0
    text = open(os.path.join(folder, f"log.{ranks}")).read()
    m = re.search(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    if not m:
        sys.exit("bench_dem: no 'Loop time' in the LAMMPS log")
    return int(m.group(4)), int(m.group(3)), float(m.group(1)), whole


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--rows", type=int, default=150)
    ap.add_argument("--cols", type=int, default=180)
    ap.add_argument("--only", choices=["lagfsi", "lammps"])
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--write-only", action="store_true", help="write the inputs and stop")
    a = ap.parse_args()
    out = os.path.abspath(a.outdir or os.path.join(a.build, "bench_dem"))
    os.makedirs(out, exist_ok=True)
    pts, width, height = bed(a.rows, a.cols)
    case = os.path.join(out, "bench_dem.json")
    write_lagfsi(case, pts, width, height, a.steps)
    lmp_dir = os.path.join(out, "lammps")
    os.makedirs(lmp_dir, exist_ok=True)
    write_lammps(lmp_dir, pts, width, height, a.steps)
    print(f"bed: {len(pts)} discs, {a.steps} steps of {DT} s; inputs in {out}")
    if a.write_only:
        return
    threads = [int(t) for t in a.threads.split(",")]
    exe = os.path.join(a.build, "lagfsi")
    rate = {}
    print("code     threads/ranks  discs  steps  loop[s]  process[s]  M particle-steps/s")
    for n in threads:
        if a.only != "lammps":
            if not os.access(exe, os.X_OK):
                sys.exit(f"bench_dem: {exe} not found (build first)")
            discs, steps, loop, whole = run_lagfsi(exe, case, os.path.join(out, f"lagfsi_{n}"), n)
            rate[("lagfsi", n)] = discs * steps / loop
            print(f"lagfsi   {n:13d}  {discs:5d}  {steps:5d}  {loop:7.2f}  {whole:10.2f}  {rate[('lagfsi', n)] / 1e6:18.2f}")
        if a.only != "lagfsi":
            discs, steps, loop, whole = run_lammps(lmp_dir, n)
            rate[("lammps", n)] = discs * steps / loop
            print(f"lammps   {n:13d}  {discs:5d}  {steps:5d}  {loop:7.2f}  {whole:10.2f}  {rate[('lammps', n)] / 1e6:18.2f}")
    for n in threads:
        if ("lagfsi", n) in rate and ("lammps", n) in rate:
            print(f"ratio lagfsi / LAMMPS at {n} thread(s)/rank(s): {rate[('lagfsi', n)] / rate[('lammps', n)]:.2f}"
                  f" (goal >= 1.5)")


if __name__ == "__main__":
    main()
