#!/usr/bin/python3
"""dem_column_collapse: final deposit of the DEM column against the run-out scalings
(reference/mpm_granular_column_collapse_scalings.csv) and against mpm_granular_collapse (same column) and Bui et
al.'s experiment (numbers quoted in cases/mpm_granular_collapse/README.md).

usage: /usr/bin/python3 cases/dem_column_collapse/plot.py OUTDIR
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
L0 = 0.2
THICK = 0.005          # "deposit at least 5 mm thick", as in mpm_granular_collapse
MPM_RUNOUT = 0.415     # mpm_granular_collapse, 2.5 mm cells, deposit >= 5 mm to (its README)
EXPERIMENT = 0.396     # Bui et al. 2008, surface drops below 5 mm (digitized, its README)


def discs(path):
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return [(float(r["x"]), float(r["y"]), float(r["r"])) for r in rows]


def profile(d, h):
    """Surface height per bin: the top of the pile connected to the floor (gaps of a diameter end it)."""
    xmax = max(x for x, _, _ in d)
    nb = int(xmax / h) + 1
    bins = [[] for _ in range(nb)]
    rmax = max(r for _, _, r in d)
    for x, y, r in d:
        bins[min(nb - 1, max(0, int(x / h)))].append((y - r, y + r))
    xs, hs = [], []
    for k, b in enumerate(bins):
        b.sort()
        top = 0.0
        if b and b[0][0] < 2 * rmax:
            top = b[0][1]
            for lo, hi in b[1:]:
                if lo > top + 2 * rmax:
                    break
                top = max(top, hi)
        xs.append((k + 0.5) * h)
        hs.append(top)
    return xs, hs


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "out")
    with open(os.path.join(out, "probes.csv")) as f:
        pr = list(csv.DictReader(f))
    h0 = float(pr[0]["height_wall"])
    a = h0 / L0
    d = discs(os.path.join(out, "column_discs.csv"))
    xs, hs = profile(d, 0.004)
    thick_to = max((x for x, hh in zip(xs, hs) if hh >= THICK), default=0.0)
    front = float(pr[-1]["runout"])
    h_end = float(pr[-1]["height_wall"])
    print(f"initial column: L0 = {L0} m, H0 = {h0:.4f} m (a = {a:.3f}); {len(d)} discs")
    print(f"final: deposit >= 5 mm thick to x = {thick_to:.3f} m, front (6th farthest disc) {front:.3f} m, "
          f"height at the wall {h_end:.4f} m (H_inf/H0 = {h_end / h0:.3f})")
    ro = (thick_to - L0) / L0
    record("h0", h0)
    record("deposit_end", thick_to)
    record("runout_ratio", ro / a)
    record("height_ratio", h_end / h0)
    print(f"run-out (L_inf - L0)/L0 = {ro:.3f} (deposit >= 5 mm)")
    for name, c in (("Lube et al. 2005 (1.2 a)", 1.2), ("Lajeunesse et al. 2005 (1.8 a)", 1.8),
                    ("Kumar 2015 2D DEM (1.67 a)", 1.67)):
        print(f"  {name}: {c * a:.3f}  -> L_inf = {L0 * (1 + c * a):.3f} m; DEM / scaling = {ro / (c * a):.2f}")
    print(f"  mpm_granular_collapse (same column, MPM): deposit >= 5 mm to {MPM_RUNOUT} m; DEM {thick_to:.3f} m "
          f"({100 * (thick_to / MPM_RUNOUT - 1):+.1f} %)")
    print(f"  Bui et al. 2008 experiment: {EXPERIMENT} m; DEM {100 * (thick_to / EXPERIMENT - 1):+.1f} %")
    fig, ax = plt.subplots(figsize=(9, 3.2))
    ax.plot(xs, hs, "k-", label="DEM final surface (t = 1 s)")
    ax.scatter([x for x, _, _ in d], [y for _, y, _ in d], s=0.3, c="0.6")
    for name, c, col in (("Lube 1.2a", 1.2, "b"), ("Lajeunesse 1.8a", 1.8, "g"), ("Kumar DEM 1.67a", 1.67, "m")):
        ax.axvline(L0 * (1 + c * a), color=col, ls="--", lw=0.8, label=name)
    ax.axvline(MPM_RUNOUT, color="r", ls=":", lw=0.8, label="MPM (>= 5 mm)")
    ax.axvline(EXPERIMENT, color="k", ls=":", lw=0.8, label="Bui 2008 exp.")
    ax.set_xlim(0, 0.6)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(fontsize=7, ncol=3)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "comparison.png"), dpi=110)


if __name__ == "__main__":
    main()
