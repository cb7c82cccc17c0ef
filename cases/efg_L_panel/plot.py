"""EFG L-panel: total load (N) against the vertical displacement of node A (mm), one curve per run directory.
Usage: /usr/bin/python3 cases/efg_L_panel/plot.py OUTDIR [OUTDIR2 ...]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

outs = sys.argv[1:] or ["out/efg_L_panel"]
fig, ax = plt.subplots(figsize=(6, 4))
peaks = []
for n, o in enumerate(outs):
    p = read_csv(os.path.join(o, "probes.csv"))
    i = max(range(len(p["load"])), key=lambda k: p["load"][k])
    peaks.append(p["load"][i])
    record("peak_load_%d" % n, p["load"][i])
    record("uy_at_peak_%d" % n, p["node_A_uy"][i])
    record("last_over_peak_%d" % n, p["load"][-1] / p["load"][i])
    print("%s: peak load %.0f N (lambda %.3f) at node_A_uy %.4f mm; last %.0f N at %.4f mm; max damage %.3f; %d steps"
          % (o, p["load"][i], p["lambda"][i], p["node_A_uy"][i], p["load"][-1], p["node_A_uy"][-1],
             p["damage_max"][-1], len(p["load"]) - 1))
    ax.plot(p["node_A_uy"], [v / 1e3 for v in p["load"]], ".-", label=os.path.basename(o.rstrip("/")))
if len(peaks) > 1:  # the thesis's finding for runs given in increasing rho: the limit load grows with rho
    record("peak_growth_min", min(b / a for a, b in zip(peaks, peaks[1:])))
ax.set_xlabel("node A vertical displacement (mm)")
ax.set_ylabel("load (kN)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, outs[0])
