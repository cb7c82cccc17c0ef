"""EFG beam with a defect: load factor against the vertical deflection of the bottom mid-span node, with the elastic
beam-theory slope (Euler-Bernoulli + shear) for orientation. Records the peak, the deflection there, the load factor
where damage starts and the drop of the load factor in one step (the snap-back GDC jumps over). For every run (index n
in the order given): the peak, the largest one-step drop, the smallest deflection after the peak (how far the path
snaps back), the last point, the load factor where the run's branch after the snap-back passes U_REF, and for arc-length runs the steps that converged off the constraint (summary.json).
Usage: /usr/bin/python3 cases/efg_defect_beam/plot.py OUTDIR [OUTDIR2 ...]"""
import json
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
u_ref = 0.31  # mm: a deflection every run reaches on its branch after the snap-back
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
    u_min = min(u[i:])
    # The load factor where the branch after the smallest deflection crosses U_REF.
    j = i + u[i:].index(u_min)
    at_ref = next((lam[k] + (lam[k + 1] - lam[k]) * (u_ref - u[k]) / (u[k + 1] - u[k])
                   for k in range(j, len(u) - 1) if u[k] <= u_ref <= u[k + 1]), float("nan"))
    print("  smallest deflection after the peak %.4f mm; lambda %.3f at %.2f mm after the snap-back"
          % (u_min, at_ref, u_ref))
    for key, v in (("peak", lam[i]), ("drop", drop), ("u_min", u_min), ("last", lam[-1]), ("u_last", u[-1]),
                   ("at_ref", at_ref)):
        record("%s_%d" % (key, n), v)
    with open(os.path.join(o, "summary.json")) as f:
        arc = json.load(f)["bodies"][0].get("arc_length")
    if arc:
        print("  arc length: %d steps off the constraint (largest |DU|/Dl %.2f), %d complex-root iterations"
              % (arc["steps_off_constraint"], arc["max_increment_ratio"], arc["complex_root_iterations"]))
        record("off_constraint_%d" % n, arc["steps_off_constraint"])
        record("increment_ratio_%d" % n, arc["max_increment_ratio"])
    if n == 0:
        record("peak", lam[i])
        record("u_at_peak", u[i])
        record("onset", onset)
        record("drop", drop)
        record("compliance", u[k1] / lam[k1])
        record("last_over_peak", lam[-1] / lam[i])
    ax.plot(u, lam, ".-", ms=3, label=os.path.basename(o.rstrip("/")))
ax.plot([0, 0.3], [0, 0.3 / slope], "k:", label="beam theory (elastic)")
ax.set_xlabel("deflection of the bottom mid-span node (mm)")
ax.set_ylabel("load factor (q = 1 N/mm)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
