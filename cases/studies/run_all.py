"""Runs every study of cases/studies/ one after the other, the cheapest first.

Usage: /usr/bin/python3 cases/studies/run_all.py [--quick] [--exe PATH] [--out DIR] [--publish] [--rerun]
                                                [--cases DIR] [--only NAME ...] [--plan DIR]
  --out DIR   root of the output folders: DIR/<study> (default <repo>/out/studies)
  --plan DIR  make no run: each study writes the runs it still needs to DIR/<study>.jsonl, to run as separate jobs
              (`jobs.py DIR/*.jsonl` under mpirun or as a job array); then run_all.py without --plan collects them
Every study gets the same --exe/--quick/--publish/--rerun. Exits non-zero if a study fails (in quick mode: its
outputs are missing or not finite). Prints the wall time of each study."""
import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
# Cheapest first (full-mode wall time on the 2-core machine, see README.md).
STUDIES = ["wall_pressure", "adaptivity", "conservation", "efg", "added_mass", "alpha_sensitivity", "convergence", "stability_map", "accuracy_walltime",
           "dem_blast", "turek_hron_fsi"]

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--exe", default=os.path.join(REPO, "build", "lagfsi"))
ap.add_argument("--out", default=os.path.join(REPO, "out", "studies"))
ap.add_argument("--cases", default=None, help="case files (default <repo>/cases)")
ap.add_argument("--quick", action="store_true")
ap.add_argument("--publish", action="store_true")
ap.add_argument("--rerun", action="store_true")
ap.add_argument("--only", nargs="*", default=None, choices=STUDIES)
ap.add_argument("--plan", metavar="DIR", default=None)
a = ap.parse_args()
if a.plan:
    os.makedirs(a.plan, exist_ok=True)

failed, times = [], []
t_all = time.time()
for name in a.only or STUDIES:
    cmd = [sys.executable, os.path.join(HERE, name, "run.py"), "--exe", a.exe, "--out", os.path.join(a.out, name)]
    cmd += [f for f, on in (("--quick", a.quick), ("--publish", a.publish), ("--rerun", a.rerun)) if on]
    cmd += ["--cases", a.cases] if a.cases else []
    cmd += ["--plan", os.path.join(a.plan, name + ".jsonl")] if a.plan else []
    print("=== %s: %s" % (name, " ".join(cmd)), flush=True)
    t = time.time()
    rc = subprocess.call(cmd)
    times.append((name, time.time() - t, rc))
    if rc != 0:
        failed.append(name)
print("\n".join("%-20s %7.1f s  %s" % (n, w, "ok" if rc == 0 else "FAILED (exit %d)" % rc) for n, w, rc in times))
print("all studies: %.1f s" % (time.time() - t_all))
sys.exit(1 if failed else 0)
