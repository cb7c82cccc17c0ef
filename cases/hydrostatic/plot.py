"""Water at rest in a tank: bottom pressure against rho g H, kinetic energy and fluid area.
Usage: /usr/bin/python3 cases/hydrostatic/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/hydrostatic")
p = read_csv(os.path.join(out, "probes.csv"))
pref = 1000 * 9.81 * 0.2
a0 = p["fluid_area"][0]
record("p_bottom_end", p["p_bottom"][-1])
record("kinetic_energy_max", max(p["kinetic_energy"]))
record("area_drift", p["fluid_area"][-1] / a0 - 1)
print("bottom pressure at the end %.2f Pa (rho g H = %.2f, %+.3f %%); max kinetic energy %.3e J; area drift %+.4f %%"
      % (p["p_bottom"][-1], pref, 100 * (p["p_bottom"][-1] / pref - 1), max(p["kinetic_energy"]),
         100 * (p["fluid_area"][-1] / a0 - 1)))
fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
axes[0].plot(p["time"], p["p_bottom"], label="lagfsi, mean over the floor sensor")
axes[0].axhline(pref, color="k", ls="--", label="rho g H")
axes[0].set_xlabel("t [s]")
axes[0].set_ylabel("pressure [Pa]")
axes[0].legend(fontsize=8)
axes[1].plot(p["time"], [100 * (a / a0 - 1) for a in p["fluid_area"]])
axes[1].set_xlabel("t [s]")
axes[1].set_ylabel("area drift [%]")
for ax in axes:
    ax.grid(alpha=0.3)
save(fig, out)
