"""EFG deep beam with overhang: load factor against the vertical displacement of node A (the bottom corner of the
loaded free end), one curve per run directory (P1 and P2). Records the peak and the displacement there for each.
Usage: /usr/bin/python3 cases/efg_deep_beam/plot.py OUTDIR [OUTDIR2 ...]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

outs = sys.argv[1:] or ["out/efg_deep_beam"]
fig, ax = plt.subplots(figsize=(6, 4))
peaks = []
for n, o in enumerate(outs):
    p = read_csv(os.path.join(o, "probes.csv"))
    lam, u = p["lambda"], [-1e3 * v for v in p["node_A_uy"]]
    i = max(range(len(lam)), key=lambda k: lam[k])
    onset = next((lam[k - 1] for k in range(1, len(lam)) if p["damage_max"][k] > 0), float("nan"))
    print("%s: peak lambda %.4f at u_A %.4f mm; damage from lambda %.4f; last lambda %.4f at %.4f mm; %d steps"
          % (o, lam[i], u[i], onset, lam[-1], u[-1], len(lam) - 1))
    peaks.append(lam[i])
    record("peak_%d" % n, lam[i])
    record("u_at_peak_%d" % n, u[i] * 1e-3)
    record("last_over_peak_%d" % n, lam[-1] / lam[i])
    ax.plot(u, lam, ".-", label=os.path.basename(o.rstrip("/")))
if len(peaks) > 1:
    record("peak_ratio", peaks[1] / peaks[0])
ax.set_xlabel("vertical displacement of node A (mm, downwards)")
ax.set_ylabel("load factor (P = 1 MN)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
