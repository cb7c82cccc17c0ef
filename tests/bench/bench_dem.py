#!/usr/bin/python3
"""Benchmark (not a test): the same 2D granular bed in lagfsi's DEM body and in LAMMPS, particle-steps per second.

The bed: about 27 000 discs (d = 2 mm, rho = 2500 kg/m^3, unit depth), 180 per row and 150 rows on a
hexagonal lattice with a 2 % gap and a small random jitter, in a box (floor and two side walls), settling under
gravity for 2000 steps of 2e-5 s. Contact law in both codes: linear spring-dashpot with a Coulomb tangential
spring with history (LAMMPS pair gran/hooke/history: Kn = 1e5 N/m, Kt = 2/7 Kn, gamma_n = 50 1/s,
gamma_t = 25 1/s (damping force m_eff gamma v), mu = 0.5; lagfsi "law": "linear", "damping": "viscous" with the
same numbers), rotation on (LAMMPS fix nve/sphere disc: I = m r^2/2), fix enforce2d, neighbour skin 0.5 mm
checked every step. The bench writes both inputs, runs lagfsi with 1 and 2 OpenMP threads and LAMMPS with 1 and
2 MPI ranks (mpirun), and prints particle-steps per second (discs x steps / loop time: LAMMPS "Loop time",
lagfsi the DEM body's wall time from summary.json) and the ratios.

The machine may be shared: each thread count is run --repeat times as pairs, lagfsi then LAMMPS, A B A B ..., so
that both see the same load; every run also records its whole-process wall and CPU time (user + system, from
the operating system's accounting of the finished child). Printed: the median of each figure and the median of
the pairwise ratios lagfsi / LAMMPS (quote medians and ratios, not single times: on a loaded machine the absolute
rates drop, the ratio much less). --wait passive makes idle threads and ranks sleep instead of spinning
(lagfsi OMP_WAIT_POLICY=passive, OpenMPI --mca mpi_yield_when_idle 1): on a machine with more runnable processes
than cores, a spinning OpenMP barrier waits for a descheduled thread several times per step (measured here at a
load of 9 on 2 cores: 2 threads 19.4 s CPU with active waiting, 1.9 s passive). --print-commands prints the two commands of each thread count (to time them
with another tool) and stops.

usage: /usr/bin/python3 tests/bench/bench_dem.py [OUTDIR] [--build DIR] [--steps 2000] [--rows 150] [--cols 180]
       [--only lagfsi|lammps] [--threads 1,2] [--repeat 3] [--wait active|passive] [--print-commands]
"""
import argparse
import json
import math
import os
import random
import re
import resource
import statistics
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


def timed(cmd, cwd=None, env=None):
    """Runs cmd; returns (wall, CPU) seconds of the whole process (CPU: user + system of the finished children)."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    subprocess.run(cmd, cwd=cwd, env=env, check=True)
    wall = time.time() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


WAIT = "active"


def lagfsi_cmd(exe, case, out, threads):
    return [exe, "run", case, "-o", out, "--quiet", "--threads", str(threads)]


def run_lagfsi(exe, case, out, threads):
    env = dict(os.environ, OMP_WAIT_POLICY=WAIT.upper())
    wall, cpu = timed(lagfsi_cmd(exe, case, out, threads), env=env)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    b = s["bodies"][0]
    return b["nodes"], b["substeps"], b["wall_time"], wall, cpu


def lammps_cmd(ranks):
    lmp = shutil.which("lmp") or shutil.which("lmp_serial")
    if not lmp:
        sys.exit("bench_dem: LAMMPS not found (apt-get install -y --no-install-recommends lammps)")
    cmd = [lmp, "-in", "in.bench", "-log", f"log.{ranks}", "-screen", "none"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe"] + \
            (["--mca", "mpi_yield_when_idle", "1"] if WAIT == "passive" else []) + ["-np", str(ranks)] + cmd
    return cmd


def run_lammps(folder, ranks):
    wall, cpu = timed(lammps_cmd(ranks), cwd=folder, env=dict(os.environ, OMP_NUM_THREADS="1"))
    text = open(os.path.join(folder, f"log.{ranks}")).read()
    m = re.search(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    if not m:
        sys.exit("bench_dem: no 'Loop time' in the LAMMPS log")
    return int(m.group(4)), int(m.group(3)), float(m.group(1)), wall, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--rows", type=int, default=150)
    ap.add_argument("--cols", type=int, default=180)
    ap.add_argument("--only", choices=["lagfsi", "lammps"])
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeat", type=int, default=3, help="pairs (lagfsi, LAMMPS) per thread count")
    ap.add_argument("--wait", choices=["active", "passive"], default="active",
                    help="idle threads/ranks spin (the runtimes' default) or sleep (for a shared machine)")
    ap.add_argument("--write-only", action="store_true", help="write the inputs and stop")
    ap.add_argument("--print-commands", action="store_true", help="print the commands of each thread count and stop")
    a = ap.parse_args()
    global WAIT
    WAIT = a.wait
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
    if a.print_commands:
        for n in threads:
            print(f"{n} thread(s)/rank(s):\n  lagfsi (OMP_WAIT_POLICY={WAIT}): {' '.join(lagfsi_cmd(exe, case, os.path.join(out, f'lagfsi_{n}'), n))}"
                  f"\n  LAMMPS (in {lmp_dir}, OMP_NUM_THREADS=1): {' '.join(lammps_cmd(n))}")
        return
    if a.only != "lammps" and not os.access(exe, os.X_OK):
        sys.exit(f"bench_dem: {exe} not found (build first)")
    runs = {}  # (code, n) -> list of (rate, wall, cpu)
    print("code     threads/ranks  run  discs  steps  loop[s]  process wall[s]  process CPU[s]  M particle-steps/s")
    for n in threads:
        for k in range(a.repeat):
            for code in ("lagfsi", "lammps"):
                if a.only and a.only != code:
                    continue
                if code == "lagfsi":
                    discs, steps, loop, wall, cpu = run_lagfsi(exe, case, os.path.join(out, f"lagfsi_{n}"), n)
                else:
                    discs, steps, loop, wall, cpu = run_lammps(lmp_dir, n)
                rate = discs * steps / loop
                runs.setdefault((code, n), []).append((rate, wall, cpu))
                print(f"{code:8s} {n:13d}  {k + 1:3d}  {discs:5d}  {steps:5d}  {loop:7.2f}  {wall:15.2f}  {cpu:14.2f}  "
                      f"{rate / 1e6:18.2f}", flush=True)
    print("medians:")
    for (code, n), v in sorted(runs.items()):
        print(f"  {code:8s} {n} thread(s)/rank(s): {statistics.median(r for r, _, _ in v) / 1e6:.2f} M particle-steps/s,"
              f" process wall {statistics.median(w for _, w, _ in v):.2f} s, CPU {statistics.median(c for _, _, c in v):.2f} s")
    for n in threads:
        if ("lagfsi", n) in runs and ("lammps", n) in runs:
            pairs = list(zip(runs[("lagfsi", n)], runs[("lammps", n)]))
            rate = statistics.median(x[0] / y[0] for x, y in pairs)
            wall = statistics.median(y[1] / x[1] for x, y in pairs)
            cpu = statistics.median(y[2] / x[2] for x, y in pairs)
            print(f"ratio lagfsi / LAMMPS at {n} thread(s)/rank(s), median of {len(pairs)} pairs: loop rate {rate:.2f},"
                  f" process wall {wall:.2f}, process CPU {cpu:.2f} (LAMMPS time / lagfsi time; goal >= 1.5)")

if __name__ == "__main__":
    main()
