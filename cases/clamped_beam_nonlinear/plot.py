"""Midspan deflection of the clamped-clamped beam (Mondkar & Powell 1977) under a step load.
Usage: /usr/bin/python3 cases/clamped_beam_nonlinear/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/clamped_beam_nonlinear")
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "seed_values.csv"))
get = lambda q: ref["value"][ref["quantity"].index(q)]
lin_peak = 2 * get("linear_static_midspan_in")
p = read_csv(os.path.join(out, "probes.csv"))
t = [1e3 * x for x in p["time"]]
peak = -min(p["mid_uy"])
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(t, [-u for u in p["mid_uy"]], label="lagfsi, geometrically nonlinear (T10)")
ax.axhline(get("nonlinear_to_linear_amplitude_ratio") * lin_peak, color="k", ls="--",
           label="seed: about 7 %% of the linear dynamic peak (%.2f in)" % lin_peak)
ax.set_title("Clamped beam, step load: peak %.3f in = %.1f %% of linear" % (peak, 100 * peak / lin_peak))
ax.set_xlabel("time [ms]")
ax.set_ylabel("midspan deflection [in]")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
