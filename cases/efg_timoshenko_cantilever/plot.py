"""EFG cantilever against the Timoshenko & Goodier solution: tip deflection, energy-norm error, and (if
convergence.py was run) the error against node spacing per basis, rho and integration.
Usage: /usr/bin/python3 cases/efg_timoshenko_cantilever/plot.py OUTDIR [CONVERGENCE_DIR]"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/efg_timoshenko_cantilever")
p = read_csv(os.path.join(out, "probes.csv"))
s = json.load(open(os.path.join(out, "summary.json")))["bodies"][0]
tip = p["tip_uy"][-1]
print("tip u_y %.6e (exact 8.9000e-03, %+.2f %%); root sigma_xx(12, 6) %.1f (exact -1500, %+.2f %%); "
      "relative energy error %.4e" % (tip, 100 * (tip / 0.0089 - 1), p["root_sxx_top"][-1],
                                      100 * (p["root_sxx_top"][-1] / -1500 - 1), s["energy_error_relative"]))
conv = sys.argv[2] if len(sys.argv) > 2 else "out/efg_cantilever_conv"
fig, ax = plt.subplots(figsize=(6.5, 4.5))
path = os.path.join(conv, "convergence.csv")
if os.path.exists(path):
    c = read_csv(path)
    cells = c.get("cells", ["q4"] * len(c["h"]))
    keys = sorted(set(zip(c["basis"], c["alpha"], c["essential"], c["integration"], cells)))
    for b, a, es, i, ce in keys:
        idx = [k for k in range(len(c["h"]))
               if (c["basis"][k], c["alpha"][k], c["essential"][k], c["integration"][k], cells[k]) == (b, a, es, i, ce)]
        h = [c["h"][k] for k in idx]
        e = [c["energy_error_relative"][k] for k in idx]
        orders = [math.log(e[k - 1] / e[k]) / math.log(h[k - 1] / h[k]) for k in range(1, len(idx))]
        print("%-11s rho=%gh %-9s %-3s %-10s errors %s orders %s" % (b, a, es, ce, i, " ".join("%.3e" % v for v in e),
                                                           " ".join("%.2f" % o for o in orders)))
        ax.loglog(h, e, "o-" if i == "gauss" else "s--", label="%s rho=%gh %s %s %s" % (b, a, es, ce, i))
    ax.set_xlabel("node spacing h")
    ax.set_ylabel("relative energy-norm error")
    ax.legend(fontsize=6)
    ax.grid(alpha=0.3, which="both")
ax.set_title("EFG Timoshenko cantilever")
save(fig, out)
