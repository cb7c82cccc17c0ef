"""EFG beam with a defect: load factor against the vertical deflection of the bottom mid-span node, with the elastic
beam-theory slope (Euler-Bernoulli + shear) for orientation. Records the peak, the deflection there, the load factor
where damage starts and the drop of the load factor in one step (the snap-back GDC jumps over).
Usage: /usr/bin/python3 cases/efg_defect_beam/plot.py OUTDIR [OUTDIR2 ...]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

outs = sys.argv[1:] or ["out/efg_defect_beam"]
L, H, B, E, NU, Q = 2000.0, 400.0, 100.0, 2e4, 0.2, 1.0
I = B * H ** 3 / 12
slope = 5 * Q * L ** 4 / (384 * E * I) + Q * L ** 2 / (8 * (5 / 6) * E / (2 * (1 + NU)) * B * H)  # mm per unit lambda
fig, ax = plt.subplots(figsize=(6, 4))
for n, o in enumerate(outs):
    p = read_csv(os.path.join(o, "probes.csv"))
    lam, u, d = p["lambda"], [-v for v in p["mid_uy"]], p["damage_max"]
    i = max(range(len(lam)), key=lambda k: lam[k])
    onset = next((lam[k - 1] for k in range(1, len(d)) if d[k] > 0), float("nan"))
    drop = max(lam[k] - lam[k + 1] for k in range(len(lam) - 1))
    k1 = 1 if len(u) > 1 else 0
    print("%s: peak lambda %.3f at %.4f mm; damage starts after lambda %.3f; largest drop in one step %.3f; "
          "initial compliance %.5f mm per unit lambda (beam theory %.5f); last lambda %.3f at %.4f mm, %d steps"
          % (o, lam[i], u[i], onset, drop, u[k1] / lam[k1], slope, lam[-1], u[-1], len(lam) - 1))
    if n == 0:
        record("peak", lam[i])
        record("u_at_peak", u[i])
        record("onset", onset)
        record("drop", drop)
        record("compliance", u[k1] / lam[k1])
        record("last_over_peak", lam[-1] / lam[i])
    ax.plot(u, lam, ".-", label=os.path.basename(o.rstrip("/")))
ax.plot([0, 0.3], [0, 0.3 / slope], "k:", label="beam theory (elastic)")
ax.set_xlabel("deflection of the bottom mid-span node (mm)")
ax.set_ylabel("load factor (q = 1 N/mm)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
