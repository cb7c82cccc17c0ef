"""Energy-norm convergence of the EFG cantilever: bases x rho x essential conditions x cells over node spacings.
Usage: /usr/bin/python3 cases/efg_timoshenko_cantilever/convergence.py [--exe build/lagfsi] [--out out/efg_cantilever_conv]
       [--quick] [--publish]
Writes OUT/convergence.csv and prints the observed order (log2 of successive error ratios) of each series. --publish
also writes reference/measured_convergence.csv and the table of README.md between its convergence markers."""
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
ap.add_argument("--quick", action="store_true", help="h = 6, 3, 1.5 (else down to 0.75)")
ap.add_argument("--publish", action="store_true", help="write reference/measured_convergence.csv and the README table")
a = ap.parse_args()
# (basis, alpha, essential conditions, integration, cells). Quadratic bases with Q4 coupling elements violate the
# coupling's continuity condition (the thesis uses Q9 there): they are run with Q4 coupling (to show it), with Q9
# cells and coupling elements (the same nodes: cells twice as wide), and with Lagrange multipliers.
series = [("linear", 2.0, "coupling", "gauss", "q4"), ("bilinear", 2.0, "coupling", "gauss", "q4"),
          ("bilinear", 3.0, "coupling", "gauss", "q4"), ("bilinear", 2.0, "coupling", "consistent", "q4"),
          ("quadratic", 3.0, "coupling", "gauss", "q4"), ("quadratic", 3.0, "coupling", "gauss", "q9"),
          ("biquadratic", 3.0, "coupling", "gauss", "q9"), ("quadratic", 3.0, "coupling", "consistent", "q9"),
          ("quadratic", 3.0, "lagrange", "gauss", "q4"), ("biquadratic", 3.0, "lagrange", "gauss", "q4")]
divs = [(8, 2), (16, 4), (32, 8)] if a.quick else [(8, 2), (16, 4), (32, 8), (64, 16)]


def gauss_of(basis, cells):
    """Points per direction: 4 x 4 per h x h cell for the linear bases, 5 x 5 for the quadratic ones; a Q9 cell is
    2h x 2h and gets 8 x 8."""
    if cells == "q9":
        return 8
    return 4 if basis in ("linear", "bilinear") else 5


rows = []
for basis, alpha, ess, integ, cells in series:
    gauss = gauss_of(basis, cells)
    for nx, ny in divs:
        cx, cy = (nx, ny) if cells == "q4" else (nx // 2, ny // 2)
        tag = "%s_a%g_%s_%s_%s_%dx%d" % (basis, alpha, ess, integ, cells, nx, ny)
        out = os.path.join(a.out, tag)
        sets = ["bodies.0.domain.divisions=[%d,%d]" % (cx, cy), "bodies.0.domain.cells=" + cells,
                "bodies.0.efg.basis=" + basis, "bodies.0.efg.alpha=%g" % alpha, "bodies.0.efg.gauss=%d" % gauss,
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
        rows.append(dict(basis=basis, alpha=alpha, essential=ess, integration=integ, cells=cells, gauss=gauss, nx=nx,
                         ny=ny, h=48.0 / nx, nodes=b["nodes"], energy_error=b["energy_error"],
                         energy_error_relative=b["energy_error_relative"], tip_uy=tip, tip_error=tip / 0.0089 - 1,
                         wall=wall, shape_us_per_point=b["shape_function_time_per_point_us"],
                         assembly=b["timing"]["assembly"], solve=b["timing"]["factorization"] + b["timing"]["solve"]))
os.makedirs(a.out, exist_ok=True)
fields = list(rows[0].keys())
with open(os.path.join(a.out, "convergence.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields)
    w.writeheader()
    w.writerows(rows)

NAMES = {"linear": "linear {1, x, y}", "bilinear": "bilinear", "quadratic": "quadratic (P2)",
         "biquadratic": "biquadratic (9 terms)"}
table = ["| basis | ρ | essential | cells | integration | " + " | ".join("h = %g" % (48.0 / nx) for nx, _ in divs) +
         " | observed order |", "|---" * (6 + len(divs)) + "|"]
print("%-11s %5s %-9s %-5s %-10s %8s %12s %10s %8s %8s" % ("basis", "alpha", "essential", "cells", "integr.", "h",
                                                          "rel. energy", "tip err", "order", "wall s"))
for basis, alpha, ess, integ, cells in series:
    sr = [r for r in rows if (r["basis"], r["alpha"], r["essential"], r["integration"], r["cells"]) ==
          (basis, alpha, ess, integ, cells)]
    orders = []
    for i, r in enumerate(sr):
        order = "" if i == 0 else "%.2f" % (math.log(sr[i - 1]["energy_error"] / r["energy_error"]) /
                                             math.log(sr[i - 1]["h"] / r["h"]))
        if order:
            orders.append(order)
        print("%-11s %5.1f %-9s %-5s %-10s %8.3f %12.4e %+10.2e %8s %8.2f" % (
            basis, alpha, ess, cells, integ, r["h"], r["energy_error_relative"], r["tip_error"], order, r["wall"]))
    errs = {r["h"]: r["energy_error_relative"] for r in sr}
    ess_text = {"coupling": "coupling " + cells.upper(), "lagrange": "Lagrange"}[ess]
    table.append("| %s | %gh | %s | %s | %s | %s | %s |" % (
        NAMES[basis], alpha, ess_text, cells.upper(), "Gauss" if integ == "gauss" else "consistent",
        " | ".join(("%.3e" % errs[48.0 / nx]) if (48.0 / nx) in errs else "—" for nx, _ in divs), ", ".join(orders)))

if a.publish:
    with open(os.path.join(here, "reference", "measured_convergence.csv"), "w", newline="") as f:
        f.write("# Measured by cases/efg_timoshenko_cantilever/convergence.py%s --publish; not a reference solution.\n"
                % (" --quick" if a.quick else ""))
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    readme = os.path.join(here, "README.md")
    text = open(readme).read()
    begin = "<!-- convergence:begin (generated by convergence.py --publish; do not edit) -->"
    end = "<!-- convergence:end -->"
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < i:
        raise SystemExit("%s: no convergence markers" % readme)
    text = text[:i + len(begin)] + "\n" + "\n".join(table) + "\n" + text[j:]
    with open(readme, "w") as f:
        f.write(text)
    print("wrote reference/measured_convergence.csv and the README table")
