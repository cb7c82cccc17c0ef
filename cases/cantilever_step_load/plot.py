"""Tip deflection of the cantilever under a step load against the Timoshenko static value and 2x it.
Usage: /usr/bin/python3 cases/cantilever_step_load/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/cantilever_step_load")
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "analytic.csv"))
static = ref["value"][ref["quantity"].index("tip_uy_static_timoshenko")]
p = read_csv(os.path.join(out, "probes.csv"))
t = [1e3 * x for x in p["time"]]
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(t, p["tip_uy_axis"], label="lagfsi (T10), beam axis at the free end")
ax.axhline(static, color="k", ls="--", label="static, Timoshenko beam: %.5f m" % static)
ax.axhline(2 * static, color="gray", ls=":", label="2 x static (undamped step response)")
peak = min(p["tip_uy_axis"])
ax.set_title("Cantilever step load (Avancini 2018, 5.5.1): peak %.5f m = %.3f x static" % (peak, peak / static))
ax.set_xlabel("time [ms]")
ax.set_ylabel("tip u_y [m]")
ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2, fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
