"""Solitary wave: free-surface elevation on the left wall, mid-tank and the right wall, with the event times
of Avancini (2018) sec. 6.9.2. Usage: /usr/bin/python3 cases/solitary_wave/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/solitary_wave")
p = read_csv(os.path.join(out, "probes.csv"))
fig, ax = plt.subplots(figsize=(9, 4))
for k, lab in (("eta_left", "left wall"), ("eta_mid", "mid-tank"), ("eta_right", "right wall")):
    ax.plot(p["time"], p[k], label=lab)
for t, lab in ((2.3, "seed: right wall"), (4.6, "seed: back at mid-tank"), (6.9, "seed: left wall")):
    ax.axvline(t, color="k", ls=":", lw=0.8)
    ax.text(t, 1.47, lab, rotation=90, fontsize=7, va="top", ha="right")
ax.set_xlabel("t [s]")
ax.set_ylabel("free-surface elevation [m]")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
