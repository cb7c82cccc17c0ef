"""Elastic obstacle hit by a dam break (Walhorn et al. 2005): horizontal displacement of the obstacle's top left
corner against the PFEM result of Idelsohn et al. (2008) (reference/idelsohn_2008_pfem_tip_ux.csv). Prints the
RMS difference over the reference's time range, both peaks, and the coupling statistics.
Usage: /usr/bin/python3 cases/elastic_obstacle_walhorn/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save, coupling_lines, peak, interp

out = out_dir_from_argv("out/elastic_obstacle_walhorn")
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "idelsohn_2008_pfem_tip_ux.csv"))
t, ux = p["time"], p["tip_ux"]
covered = [(tr, ur) for tr, ur in zip(ref["time"], ref["tip_ux"]) if tr <= t[-1]]
rms = math.sqrt(sum((interp(tr, t, ux) - ur) ** 2 for tr, ur in covered) / len(covered))
tp, up = peak(t, ux)
trp, urp = peak(ref["time"], ref["tip_ux"])
lines = ["tip_ux: RMS difference to Idelsohn et al. 2008 %.1f mm over 0-%.2f s; peak %.1f mm at %.3f s "
         "(reference %.1f mm at %.3f s)" % (1e3 * rms, covered[-1][0], 1e3 * up, tp, 1e3 * urp, trp)]
lines += coupling_lines(out)
print("\n".join(lines))

fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
axes[0].plot(t, [1e3 * u for u in ux], label="lagfsi")
axes[0].plot(ref["time"], [1e3 * u for u in ref["tip_ux"]], "k--", lw=1, label="Idelsohn et al. 2008 (PFEM)")
axes[0].set_ylabel("tip u_x [mm]")
axes[1].plot(t, [1e3 * u for u in p["tip_uy"]], label="lagfsi")
axes[1].set_ylabel("tip u_y [mm]")
axes[1].set_xlabel("t [s]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_title("elastic obstacle: " + lines[0], fontsize=9)
save(fig, out)
