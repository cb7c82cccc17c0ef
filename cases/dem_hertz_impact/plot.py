#!/usr/bin/python3
"""dem_hertz_impact: contact force against time for Chung & Ooi (2011) tests 1 (glass sphere on glass sphere,
+-10 m/s) and 2 (Al-alloy sphere on a rigid wall, 0.2 m/s), and the contact duration, peak force and peak overlap
against Hertz (reference/dem_hertz_impact_chung_ooi_analytic.csv).

usage: /usr/bin/python3 cases/dem_hertz_impact/plot.py OUTDIR   (the output folder of `lagfsi run`)
"""
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from claims_record import record  # noqa: E402  (numbers for scripts/claims.py)


def read(path):
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    head = rows[0]
    return {h: [r[i] for r in rows[1:]] for i, h in enumerate(head)}


def impact(t, overlap, force):
    fmax = max(force)
    dmax = max(overlap)
    tc = float("nan")
    for i in range(1, len(t)):
        if overlap[i - 1] > 0 and overlap[i] <= 0:
            tc = t[i - 1] + (t[i] - t[i - 1]) * overlap[i - 1] / (overlap[i - 1] - overlap[i])
            break
    return tc, fmax, dmax


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "out")
    p = read(os.path.join(out, "probes.csv"))
    t = [float(x) for x in p["time"]]
    ref = read(os.path.join(HERE, "reference", "dem_hertz_impact_chung_ooi_analytic.csv"))
    row = {m: i for i, m in enumerate(ref["material"])}
    cases = [
        ("Test 1: glass sphere on glass sphere, 20 m/s", "glass",
         [0.02 - (float(b) - float(a)) for a, b in zip(p["pair_x0"], p["pair_x1"])], [float(x) for x in p["pair_force"]]),
        ("Test 2: Al-alloy sphere on a rigid wall, 0.2 m/s", "Al_alloy",
         [0.1 - float(y) for y in p["wall_y"]], [float(x) for x in p["wall_force"]]),
    ]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, (title, mat, ov, fo) in zip(axes, cases):
        i = row[mat]
        tc_ref, f_ref, d_ref = float(ref["t_c_s"][i]), float(ref["F_max_N"][i]), float(ref["delta_max_m"][i])
        tc, fm, dm = impact(t, ov, fo)
        record(f"{mat}_tc", tc)
        record(f"{mat}_fmax", fm)
        record(f"{mat}_dmax", dm)
        print(f"{title}: t_c {tc:.6g} s (Hertz {tc_ref:.6g}, {100 * (tc / tc_ref - 1):+.3f} %), "
              f"F_max {fm:.6g} N ({f_ref:.6g}, {100 * (fm / f_ref - 1):+.3f} %), "
              f"delta_max {dm:.6g} m ({d_ref:.6g}, {100 * (dm / d_ref - 1):+.3f} %)")
        n = sum(1 for x in t if x <= 1.3 * tc_ref)
        ax.plot([x * 1e6 for x in t[:n]], fo[:n], label="lagfsi DEM (Hertz-Mindlin)")
        ax.axhline(f_ref, color="k", ls="--", lw=0.8, label="Hertz F_max")
        ax.axvline(tc_ref * 1e6, color="r", ls=":", lw=0.8, label="Hertz t_c")
        ax.set_xlabel("t [us]")
        ax.set_ylabel("contact force [N]")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "comparison.png"), dpi=110)


if __name__ == "__main__":
    main()
