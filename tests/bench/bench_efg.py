#!/usr/bin/python3
"""Benchmark (not a test): EFG against the T6 positional solid on the Timoshenko cantilever at equal error.

The problem of cases/efg_timoshenko_cantilever: L = 48, D = 12, E = 3e7, nu = 0.3, plane stress, unit thickness,
parabolic end shear P, the exact displacements on x = 0. Both codes run it through `lagfsi run`, one thread:
  - EFG: the case file at h = 48/nx (bilinear basis, rho = 2h, 4 x 4 Gauss, Q4 cells; and the complete quadratic
    basis with Q9 cells and coupling, rho = 3h, 8 x 8 Gauss per Q9 cell);
  - T6: a `solid` body (positional FEM, Saint Venant-Kirchhoff), structured T6 mesh nx x ny ("crossed" pattern off:
    "right"), static, one load step, the exact displacements prescribed at the nodes of x = 0, the consistent nodal
    forces of the parabolic shear (3-point Gauss per quadratic edge) as point loads on x = L. The solid is
    geometrically nonlinear, so it runs with P = 1 (the EFG with P = 1000): every error below is relative; at P = 1
    the strains are ~1e-6, the nonlinear terms ~1e-6 of the response, and the round-off of the positional strain
    (F^T F - I) / 2 stays ~1e-10 of it (at P = 1e-3 it spoiled the error below 1e-3).
The energy-norm error of the T6 solution, [1/2 int (eps - eps_ex)^T D (eps - eps_ex)]^1/2 over its exact value, is
computed here from the nodal displacements of the .vtu (a 7-point degree-5 rule per triangle); the EFG's comes from
its summary.json (the same definition on its Gauss points). Times: the solver's wall time in summary.json (set-up,
assembly, factorization, solve; the output's time subtracted: the T6 run writes the .vtu the error is computed
from) and the process wall time; the best of --repeat runs. The wall time of each method at a given
error is interpolated in log-log between its two bracketing meshes; the ratio EFG/T6 is printed for a set of errors.

usage: /usr/bin/python3 tests/bench/bench_efg.py [OUTDIR] [--build DIR] [--repeat 3] [--quick]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "cases", "tools"))
from lagfsi_post.vtkxml import read_pvd, read_vtk  # noqa: E402

L, D, E, NU = 48.0, 12.0, 3e7, 0.3
I = D ** 3 / 12.0
P_SOLID = 1.0


def exact_u(x, y, P):
    ux = -P * y / (6 * E * I) * ((6 * L - 3 * x) * x + (2 + NU) * (y * y - D * D / 4))
    uy = P / (6 * E * I) * (3 * NU * y * y * (L - x) + (4 + 5 * NU) * D * D * x / 4 + (3 * L - x) * x * x)
    return ux, uy


def exact_sigma(x, y, P):
    return np.array([-P * (L - x) * y / I, 0.0 * x, P / (2 * I) * (D * D / 4 - y * y)])


def dmat():
    c = E / (1 - NU * NU)
    return np.array([[c, c * NU, 0], [c * NU, c, 0], [0, 0, c * (1 - NU) / 2]])


def run(exe, case, out, sets):
    cmd = [exe, "run", case, "-o", out, "--quiet", "--threads", "1"]
    for s in sets:
        cmd += ["--set", s]
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    wall = time.time() - t
    if p.returncode != 0:
        raise SystemExit("failed: %s\n%s" % (" ".join(cmd), p.stderr[-600:]))
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f), wall


def efg(exe, out, nx, basis, repeat):
    q9 = basis in ("quadratic", "biquadratic")
    div = [nx // 2, nx // 8] if q9 else [nx, nx // 4]
    sets = ["bodies.0.domain.divisions=[%d,%d]" % tuple(div), "bodies.0.efg.basis=" + basis,
            "bodies.0.efg.alpha=%g" % (3.0 if q9 else 2.0), "bodies.0.efg.gauss=%d" % (8 if q9 else 4),
            "bodies.0.domain.cells=" + ("q9" if q9 else "q4"), "output.vtk=false",
            "analysis.linear_solver.type=cholmod"]
    best = None
    for _ in range(repeat):
        s, wall = run(exe, os.path.join(REPO, "cases", "efg_timoshenko_cantilever", "case.json"),
                      os.path.join(out, "efg_%s_%d" % (basis, nx)), sets)
        if best is None or s["wall_time"] - s["timing"].get("output", 0) < best[0]["wall_time"] - best[0]["timing"].get("output", 0):
            best = (s, wall)
    s, wall = best
    b = s["bodies"][0]
    t = b["timing"]
    return {"method": "EFG " + basis, "nx": nx, "h": L / nx, "dofs": b["dofs"], "error": b["energy_error_relative"],
            "solver_wall": s["wall_time"] - s["timing"].get("output", 0.0), "newton": s["newton_iterations"]["total"], "process_wall": wall, "shape": b["shape_function_time"],
            "assembly": t.get("assembly", 0.0), "linear_solve": t.get("factorization", 0.0) + t.get("solve", 0.0),
            "points": b["gauss_points"]}


def t6_case(path, nx):
    ny = nx // 4
    # nodes of the T6 structured mesh on x = 0 and x = L: spacing h/2
    n_edge = 2 * ny + 1
    ys = [-D / 2 + D * k / (2 * ny) for k in range(n_edge)]
    bcs = []
    for y in ys:
        ux, uy = exact_u(0.0, y, P_SOLID)
        bcs.append({"type": "prescribed_displacement", "select": {"type": "point", "at": [0.0, y]},
                    "value": [ux, uy]})
    # consistent nodal forces of t_y = P/(2I)(D^2/4 - y^2) on x = L over quadratic edges (3-point Gauss: exact)
    f = [0.0] * n_edge
    g, w = np.polynomial.legendre.leggauss(3)
    for e in range(ny):
        y0, y2 = ys[2 * e], ys[2 * e + 2]
        for gi, wi in zip(g, w):
            y = 0.5 * (y0 + y2) + 0.5 * (y2 - y0) * gi
            ty = P_SOLID / (2 * I) * (D * D / 4 - y * y)
            N = [gi * (gi - 1) / 2, 1 - gi * gi, gi * (gi + 1) / 2]
            for a in range(3):
                f[2 * e + a] += N[a] * ty * wi * 0.5 * (y2 - y0)
    loads = [{"type": "point_load", "select": {"type": "point", "at": [L, y]}, "value": [0.0, fy]}
             for y, fy in zip(ys, f)]
    case = {
        "name": "bench_efg_t6",
        "analysis": {"type": "static", "load_steps": 1,
                     "newton": {"max_iterations": 10, "residual_tolerance": 1e-12},
                     "linear_solver": {"type": "cholmod"}},
        "bodies": [{
            "name": "beam", "type": "solid",
            "material": {"type": "svk", "young": E, "poisson": NU, "density": 1.0, "hypothesis": "plane_stress"},
            "thickness": 1.0,
            "geometry": {"type": "rectangle", "origin": [0, -D / 2], "size": [L, D]},
            "mesh": {"type": "structured", "size": L / nx, "divisions": [nx, ny], "order": 2, "pattern": "right"},
            "boundary_conditions": bcs, "loads": loads}],
        "output": {"every": 1}}
    with open(path, "w") as fh:
        json.dump(case, fh)


# 7-point degree-5 rule on the reference triangle (Dunavant): barycentric (a, b, b); weights sum to 1 (the area factor cancels in the ratio).
_A1, _B1 = 0.059715871789770, 0.470142064105115
_A2, _B2 = 0.797426985353087, 0.101286507323456
QP = [(1 / 3, 1 / 3, 0.225)]
for a, b, wq in ((_A1, _B1, 0.132394152788506), (_A2, _B2, 0.125939180544827)):
    QP += [(a, b, wq), (b, a, wq), (b, b, wq)]


def t6_error(out):
    series = read_pvd(os.path.join(out, "beam.pvd"))
    d = read_vtk(series[-1][1])
    X = np.asarray(d.points)[:, :2]
    u = np.asarray(d.point_data["displacement"])[:, :2]
    X = X - u   # the .vtu holds current positions
    conn = np.asarray(d.connectivity).reshape(-1, 6)
    Dm = dmat()
    err = ref = 0.0
    for el in conn:
        xe, ue = X[el], u[el]
        for l1, l2, wq in QP:
            l0 = 1 - l1 - l2
            # T6 (vertices 0,1,2; edges 01, 12, 20) derivatives with respect to (l1, l2), l0 = 1 - l1 - l2
            dN1 = np.array([-(4 * l0 - 1), 4 * l1 - 1, 0, 4 * (l0 - l1), 4 * l2, -4 * l2])
            dN2 = np.array([-(4 * l0 - 1), 0, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)])
            N = np.array([l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2,
                          4 * l2 * l0])
            J = np.array([dN1 @ xe, dN2 @ xe])   # rows: d/dl1, d/dl2 of (x, y)
            det = np.linalg.det(J)
            g = np.linalg.solve(J, np.vstack([dN1, dN2]))   # dN/dx, dN/dy
            gu = g @ ue   # [[dux/dx, duy/dx], [dux/dy, duy/dy]]
            eps = np.array([gu[0, 0], gu[1, 1], gu[1, 0] + gu[0, 1]])
            x, y = N @ xe
            s_ex = exact_sigma(x, y, P_SOLID)
            e_ex = np.linalg.solve(Dm, s_ex)
            de = eps - e_ex
            err += 0.5 * de @ Dm @ de * wq * det
            ref += 0.5 * e_ex @ Dm @ e_ex * wq * det
    return math.sqrt(err / ref)


def t6(exe, out, nx, repeat):
    folder = os.path.join(out, "t6_%d" % nx)
    os.makedirs(folder, exist_ok=True)
    case = os.path.join(out, "t6_%d.json" % nx)
    t6_case(case, nx)
    best = None
    for _ in range(repeat):
        s, wall = run(exe, case, folder, [])
        if best is None or s["wall_time"] - s["timing"].get("output", 0) < best[0]["wall_time"] - best[0]["timing"].get("output", 0):
            best = (s, wall)
    s, wall = best
    t = s["bodies"][0].get("timing", {})
    return {"method": "T6 solid", "nx": nx, "h": L / nx, "dofs": 2 * s["bodies"][0]["nodes"],
            "error": t6_error(folder), "solver_wall": s["wall_time"] - s["timing"].get("output", 0.0),
            "newton": s["newton_iterations"]["total"], "process_wall": wall, "shape": 0.0,
            "assembly": t.get("assembly", float("nan")),
            "linear_solve": t.get("factorization", 0.0) + t.get("solve", 0.0), "points": float("nan")}


def time_at(rows, err):
    """log-log interpolation of the solver wall time at a given error (None outside the measured range)."""
    pts = sorted((r["error"], r["solver_wall"]) for r in rows)
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if e0 <= err <= e1:
            s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=os.path.join(REPO, "out", "bench_efg"))
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    exe = os.path.join(a.build, "lagfsi")
    os.makedirs(a.out, exist_ok=True)
    levels = [8, 16, 32] if a.quick else [8, 16, 32, 64, 128]
    rows = {"EFG bilinear": [efg(exe, a.out, n, "bilinear", a.repeat) for n in levels],
            "EFG quadratic": [efg(exe, a.out, n, "quadratic", a.repeat) for n in levels],
            "T6 solid": [t6(exe, a.out, n, a.repeat) for n in (levels + ([256] if not a.quick else []))]}
    print("%-14s %5s %7s %8s %11s %9s %9s %9s %9s %9s %6s" % ("method", "nx", "h", "dofs", "rel. error", "solver s",
                                                                "process s", "shape s", "assembly", "lin.solve",
                                                                "newton"))
    for k, rs in rows.items():
        for r in rs:
            print("%-14s %5d %7.3f %8d %11.4e %9.4f %9.4f %9.4f %9.4f %9.4f %6d" % (
                k, r["nx"], r["h"], r["dofs"], r["error"], r["solver_wall"], r["process_wall"], r["shape"],
                r["assembly"], r["linear_solve"], r["newton"]))
    print("\nsolver wall time at equal relative energy-norm error (log-log interpolation), ratio EFG / T6:")
    for err in (3e-2, 1e-2, 3e-3, 1e-3, 3e-4):
        tt = time_at(rows["T6 solid"], err)
        line = "  error %.0e: T6 %s" % (err, "%.4f s" % tt if tt else "—")
        for k in ("EFG bilinear", "EFG quadratic"):
            te = time_at(rows[k], err)
            line += "; %s %s" % (k, ("%.4f s (ratio %.1f)" % (te, te / tt)) if te and tt else "—")
        print(line)
    with open(os.path.join(a.out, "bench_efg.json"), "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
