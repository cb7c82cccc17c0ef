"""EFG plate in tension (Mazars): load factor against the displacement of the loaded edge, with the homogeneous
solution (peak lambda = 2 at u = 1e-4 m). Usage: /usr/bin/python3 cases/efg_tension_plate/plot.py OUTDIR [OUTDIR2 ...]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

outs = sys.argv[1:] or ["out/efg_tension_plate"]
fig, ax = plt.subplots(figsize=(6, 4))
E, k0, At, Bt = 2e4, 1e-4, 0.95, 1e4
us = [i * 3e-6 for i in range(0, 200)]
lam = [E * u if u <= k0 else E * (k0 * (1 - At) + At * u * math.exp(-Bt * (u - k0))) for u in us]
ax.plot([1e3 * u for u in us], lam, "k--", label="homogeneous solution")
for n, o in enumerate(outs):
    p = read_csv(os.path.join(o, "probes.csv"))
    i = max(range(len(p["lambda"])), key=lambda k: p["lambda"][k])
    if n == 0:
        record("u_at_peak", p["u_A"][i])
    print("%s: peak lambda %.4f at u_A %.4e m (homogeneous 2.0 at 1e-4); last lambda %.4f at u_A %.4e, max damage %.3f, "
          "%d steps" % (o, p["lambda"][i], p["u_A"][i], p["lambda"][-1], p["u_A"][-1], p["damage_max"][-1],
                        len(p["lambda"]) - 1))
    ax.plot([1e3 * u for u in p["u_A"]], p["lambda"], ".-", label=os.path.basename(o.rstrip("/")))
ax.set_xlabel("u_A (mm)")
ax.set_ylabel("load factor")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
