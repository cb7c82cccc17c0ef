"""EFG L-panel: total load (N) against the vertical displacement of node A (mm), one curve per run directory.
Usage: /usr/bin/python3 cases/efg_L_panel/plot.py OUTDIR [OUTDIR2 ...]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, save

outs = sys.argv[1:] or ["out/efg_L_panel"]
fig, ax = plt.subplots(figsize=(6, 4))
for o in outs:
    p = read_csv(os.path.join(o, "probes.csv"))
    i = max(range(len(p["load"])), key=lambda k: p["load"][k])
    print("%s: peak load %.0f N (lambda %.3f) at node_A_uy %.4f mm; last %.0f N at %.4f mm; max damage %.3f; %d steps"
          % (o, p["load"][i], p["lambda"][i], p["node_A_uy"][i], p["load"][-1], p["node_A_uy"][-1],
             p["damage_max"][-1], len(p["load"]) - 1))
    ax.plot(p["node_A_uy"], [v / 1e3 for v in p["load"]], ".-", label=os.path.basename(o.rstrip("/")))
ax.set_xlabel("node A vertical displacement (mm)")
ax.set_ylabel("load (kN)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
