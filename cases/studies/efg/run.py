"""Study: accuracy against cost of the EFG module on the Timoshenko cantilever.

cases/efg_timoshenko_cantilever (L = 48, D = 12, parabolic end shear; exact displacements on x = 0 through the FE-EFG
coupling, the exact traction on x = L) with one parameter varied at a time around the case's settings (bilinear
basis, cubic spline, rectangular domains, rho = 2h, 4 x 4 Gauss per cell, 32 x 8 cells: h = 1.5):
  rho   alpha = rho/h in {1, 1.5, 2, 2.5, 3, 4} (5 x 5 Gauss)
  weight  cubic spline, quartic spline, exponential (a = 0.3), alternative quartic
  gauss   2 ... 8 points per direction (bilinear, Q4 cells) and 3 ... 10 (quadratic basis, Q9 cells)
  basis   linear / bilinear (Q4 cells and coupling) and quadratic / biquadratic (Q9 cells and coupling, rho = 3h)
          over node spacings h = 6, 3, 1.5, 0.75: error against wall time, with the observed orders.
Per run: relative energy-norm error, tip-deflection error, mean support size, the solver's wall time (summary.json;
one thread) and its parts (shape functions, assembly, factorization + solve).
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

S = common.Study("efg", __doc__.splitlines()[0])
CASE = "efg_timoshenko_cantilever/case.json"
L, TIP = 48.0, 0.0089
if S.quick:
    BASE_DIV, ALPHAS, WEIGHTS = (8, 2), [2.0, 3.0], ["quartic_spline"]
    GAUSS_LIN, GAUSS_QUAD = [2], [6]
    LEVELS = [(8, 2), (16, 4)]
else:
    BASE_DIV, ALPHAS = (32, 8), [1.0, 1.5, 2.0, 2.5, 3.0, 4.0]
    WEIGHTS = ["cubic_spline", "quartic_spline", "exponential", "quartic_alt"]
    GAUSS_LIN, GAUSS_QUAD = [2, 3, 4, 5, 6, 8], [3, 4, 5, 6, 8, 10]
    LEVELS = [(8, 2), (16, 4), (32, 8), (64, 16)]
# basis -> (cells, alpha, Gauss points per cell); Q9 cells are twice as wide (the same nodes), so twice the points.
BASES = {"linear": ("q4", 2.0, 4), "bilinear": ("q4", 2.0, 4), "quadratic": ("q9", 3.0, 8),
         "biquadratic": ("q9", 3.0, 8)}


def run(tag, div, basis="bilinear", alpha=2.0, weight="cubic_spline", gauss=4, cells="q4"):
    nx, ny = div if cells == "q4" else (div[0] // 2, div[1] // 2)
    sets = {"bodies.0.domain.divisions": [nx, ny], "bodies.0.domain.cells": cells, "bodies.0.efg.basis": basis,
            "bodies.0.efg.alpha": alpha, "bodies.0.efg.weight": weight, "bodies.0.efg.gauss": gauss,
            "analysis.linear_solver.type": "umfpack", "output.vtk": False}
    r = S.run(CASE, tag, sets, timeout=1200)
    row = {"tag": tag, "basis": basis, "cells": cells, "alpha": alpha, "weight": weight, "gauss": gauss,
           "h": L / div[0], "exit_code": r.rc, "energy_error": float("nan"), "tip_error": float("nan"),
           "wall_s": r.solver_wall}
    if r.ok:
        b = r.summary["bodies"][0]
        t = b.get("timing", {})
        row.update(energy_error=b["energy_error_relative"], tip_error=r.probes()["tip_uy"][-1] / TIP - 1,
                   nodes=b["nodes"], gauss_points=b["gauss_points"], support_mean=b["support_mean"],
                   shape_s=b["shape_function_time"], assembly_s=t.get("assembly", float("nan")),
                   solve_s=t.get("factorization", 0.0) + t.get("solve", 0.0), rcond_min=b["moment_rcond_min"])
    else:
        row["message"] = r.message[:160]
    return row


COLS = ["tag", "basis", "cells", "alpha", "weight", "gauss", "h", "exit_code", "energy_error", "tip_error", "nodes",
        "gauss_points", "support_mean", "rcond_min", "shape_s", "assembly_s", "solve_s", "wall_s", "order", "message"]
rho = [run("rho_a%g" % a, BASE_DIV, alpha=a, gauss=5) for a in ALPHAS]
S.table("efg_rho.csv", rho, COLS)
weight = [run("weight_" + w, BASE_DIV, weight=w) for w in WEIGHTS]
S.table("efg_weight.csv", weight, COLS)
gauss = [run("gauss_bilinear_%d" % g, BASE_DIV, gauss=g) for g in GAUSS_LIN]
gauss += [run("gauss_quadratic_%d" % g, BASE_DIV, basis="quadratic", alpha=3.0, gauss=g, cells="q9")
          for g in GAUSS_QUAD]
S.table("efg_gauss.csv", gauss, COLS)
basis = []
for b, (cells, a, g) in BASES.items():
    rows = [run("basis_%s_%dx%d" % (b, nx, ny), (nx, ny), basis=b, alpha=a, gauss=g, cells=cells) for nx, ny in LEVELS]
    for k in range(1, len(rows)):
        e0, e1 = rows[k - 1]["energy_error"], rows[k]["energy_error"]
        rows[k]["order"] = math.log(e0 / e1) / math.log(2.0) if e0 > 0 and e1 > 0 else float("nan")
    basis += rows
S.table("efg_basis.csv", basis, COLS)

fig, ax = plt.subplots(2, 2, figsize=(12, 9))
a = ax[0, 0]
ok = [r for r in rho if r["exit_code"] == 0]
a.semilogy([r["alpha"] for r in ok], [r["energy_error"] for r in ok], "o-", label="energy error")
a2 = a.twinx()
a2.plot([r["alpha"] for r in ok], [r["wall_s"] for r in ok], "s--", color="C1", label="wall time")
a.set_xlabel("rho / h")
a.set_ylabel("relative energy-norm error")
a2.set_ylabel("wall time [s]", color="C1")
a.set_title("influence radius (bilinear, h = %g)" % (L / BASE_DIV[0]))
a.grid(alpha=0.3)
a = ax[0, 1]
ok = [r for r in weight if r["exit_code"] == 0]
a.bar(range(len(ok)), [r["energy_error"] for r in ok])
a.set_xticks(range(len(ok)))
a.set_xticklabels([r["weight"] for r in ok], fontsize=8)
a.set_ylabel("relative energy-norm error")
a.set_title("weight function (bilinear, rho = 2h)")
a = ax[1, 0]
for b, c in (("bilinear", "C0"), ("quadratic", "C2")):
    ok = [r for r in gauss if r["basis"] == b and r["exit_code"] == 0]
    a.semilogy([r["gauss"] for r in ok], [r["energy_error"] for r in ok], "o-", color=c, label=b + " error")
a.set_xlabel("Gauss points per direction and cell (Q9 cells are 2h wide)")
a.set_ylabel("relative energy-norm error")
a.legend(fontsize=8)
a.grid(alpha=0.3)
a.set_title("integration order")
a = ax[1, 1]
for k, b in enumerate(BASES):
    ok = [r for r in basis if r["basis"] == b and r["exit_code"] == 0]
    a.loglog([r["wall_s"] for r in ok], [r["energy_error"] for r in ok], "o-", color="C%d" % k,
             label="%s (%s, rho = %gh)" % (b, BASES[b][0].upper(), BASES[b][1]))
a.set_xlabel("wall time [s] (one thread)")
a.set_ylabel("relative energy-norm error")
a.legend(fontsize=8)
a.grid(alpha=0.3, which="both")
a.set_title("accuracy against cost, h = 6 ... %g" % (L / LEVELS[-1][0]))
fig.suptitle("EFG Timoshenko cantilever: parameters against error and cost")
S.figure(fig, "efg_study.png")



def md_table(rows):
    """Markdown rows of the README table (one per run)."""
    out = ["| sweep | basis | cells | ρ/h | weight | Gauss | h | rel. energy error | tip error | mean support | "
           "wall s (shape / assembly / solve) | order |", "|---" * 12 + "|"]
    for sweep, rs in rows:
        for r in rs:
            if r["exit_code"] != 0:
                out.append("| %s | %s | %s | %g | %s | %d | %g | failed: %s | | | | |" % (
                    sweep, r["basis"], r["cells"].upper(), r["alpha"], r["weight"], r["gauss"], r["h"],
                    r.get("message", "")[:90].replace("|", "/")))
                continue
            out.append("| %s | %s | %s | %g | %s | %d | %g | %.3e | %+.1e | %.1f | %.2f (%.2f / %.2f / %.2f) | %s |" % (
                sweep, r["basis"], r["cells"].upper(), r["alpha"], r["weight"], r["gauss"], r["h"], r["energy_error"],
                r["tip_error"], r["support_mean"], r["wall_s"], r["shape_s"], r["assembly_s"], r["solve_s"],
                ("%.2f" % r["order"]) if "order" in r else ""))
    return "\n".join(out)


S.readme_table(md_table([("ρ", rho), ("weight", weight), ("Gauss", gauss), ("basis", basis)]))

S.finish([("efg_rho.csv", "energy_error"), ("efg_weight.csv", "energy_error"), ("efg_gauss.csv", "energy_error"),
          ("efg_basis.csv", "energy_error")])
