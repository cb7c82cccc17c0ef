"""Energy-norm convergence of the EFG cantilever: bases x rho x integration over node spacings.
Usage: /usr/bin/python3 cases/efg_timoshenko_cantilever/convergence.py [--exe build/lagfsi] [--out out/efg_cantilever_conv]
Writes OUT/convergence.csv and prints the observed order (log2 of successive error ratios) of each series."""
import argparse
import csv
import json
import math
import os
import subprocess
import time

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--exe", default=os.path.join(here, "..", "..", "build", "lagfsi"))
ap.add_argument("--out", default="out/efg_cantilever_conv")
ap.add_argument("--quick", action="store_true")
a = ap.parse_args()
# (basis, alpha, essential conditions, integration). Quadratic bases with Q4 coupling elements violate the coupling's
# continuity condition (the thesis uses Q9 there), so they are also run with Lagrange multipliers.
series = [("linear", 2.0, "coupling", "gauss"), ("bilinear", 2.0, "coupling", "gauss"),
          ("bilinear", 3.0, "coupling", "gauss"), ("bilinear", 2.0, "coupling", "consistent"),
          ("quadratic", 3.0, "coupling", "gauss"), ("quadratic", 3.0, "lagrange", "gauss"),
          ("quadratic", 3.0, "lagrange", "consistent"), ("biquadratic", 3.0, "lagrange", "gauss")]
divs = [(8, 2), (16, 4), (32, 8)] if a.quick else [(8, 2), (16, 4), (32, 8), (64, 16)]
rows = []
if True:
    for basis, alpha, ess, integ in series:
        gauss = 4 if basis in ("linear", "bilinear") else 5
        for nx, ny in divs:
            tag = "%s_a%g_%s_%s_%dx%d" % (basis, alpha, ess, integ, nx, ny)
            out = os.path.join(a.out, tag)
            sets = ["bodies.0.domain.divisions=[%d,%d]" % (nx, ny), "bodies.0.efg.basis=" + basis,
                    "bodies.0.efg.alpha=%g" % alpha, "bodies.0.efg.gauss=%d" % gauss,
                    "bodies.0.efg.integration=" + integ, "bodies.0.essential.method=" + ess,
                    "analysis.linear_solver.type=umfpack", "output.vtk=false"]
            cmd = [a.exe, "run", os.path.join(here, "case.json"), "-o", out, "--quiet", "--threads", "1"]
            for s in sets:
                cmd += ["--set", s]
            t0 = time.time()
            r = subprocess.run(cmd, capture_output=True, text=True)
            wall = time.time() - t0
            if r.returncode != 0:
                print(tag, "FAILED", r.stderr.strip())
                continue
            s = json.load(open(os.path.join(out, "summary.json")))
            b = s["bodies"][0]
            with open(os.path.join(out, "probes.csv")) as f:
                tip = float(list(csv.DictReader(f))[-1]["tip_uy"])
            rows.append(dict(basis=basis, alpha=alpha, essential=ess, integration=integ, gauss=gauss, nx=nx, ny=ny,
                             h=48.0 / nx, nodes=b["nodes"], energy_error=b["energy_error"],
                             energy_error_relative=b["energy_error_relative"], tip_uy=tip,
                             tip_error=tip / 0.0089 - 1, wall=wall,
                             shape_us_per_point=b["shape_function_time_per_point_us"],
                             assembly=b["timing"]["assembly"], solve=b["timing"]["factorization"] + b["timing"]["solve"]))
os.makedirs(a.out, exist_ok=True)
with open(os.path.join(a.out, "convergence.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)
print("%-11s %5s %-9s %-10s %8s %12s %10s %8s %8s" % ("basis", "alpha", "essential", "integr.", "h", "rel. energy",
                                                      "tip err", "order", "wall s"))
if True:
    for basis, alpha, ess, integ in series:
        sr = [r for r in rows if r["basis"] == basis and r["alpha"] == alpha and r["integration"] == integ
              and r["essential"] == ess]
        for i, r in enumerate(sr):
            order = "" if i == 0 else "%.2f" % (math.log(sr[i - 1]["energy_error"] / r["energy_error"]) /
                                                 math.log(sr[i - 1]["h"] / r["h"]))
            print("%-11s %5.1f %-9s %-10s %8.3f %12.4e %+10.2e %8s %8.2f" % (
                basis, alpha, ess, integ, r["h"], r["energy_error_relative"], r["tip_error"], order, r["wall"]))
