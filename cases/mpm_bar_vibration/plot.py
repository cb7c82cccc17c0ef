"""Vibrating bar (MPM): tip displacement and energies against the analytic first mode
(reference/mpm_bar_axial_vibration_analytic.csv, case fixed_free_mode1). Prints the period (upward zero
crossings of the tip displacement) and the largest deviation of the total energy.
Usage: /usr/bin/python3 cases/mpm_bar_vibration/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/mpm_bar_vibration")
p = read_csv(os.path.join(out, "probes.csv"))
t, u = p["time"], p["tip_u"]
L, E, rho, v0, height = 25.0, 100.0, 1.0, 0.1, 0.5
beta = math.pi / (2 * L)
omega = beta * math.sqrt(E / rho)
x_tip = 24.875  # the probed particle
ups = [t[i - 1] + (t[i] - t[i - 1]) * (-u[i - 1]) / (u[i] - u[i - 1]) for i in range(1, len(u)) if u[i - 1] < 0 <= u[i]]
period = (ups[-1] - ups[0]) / (len(ups) - 1) if len(ups) > 1 else float("nan")
e0 = p["total"][0]
dev = max((abs(e / e0 - 1) for e in p["total"]))
record("period", period)
record("energy_deviation", dev)
lines = ["period %.4f s (analytic %.4f s, %+.3f %%); total energy within %.3f %% of its initial value "
         "%.5f J/m (analytic rho v0^2 L/4 x height = %.5f)" %
         (period, 2 * math.pi / omega, 100 * (period * omega / (2 * math.pi) - 1), 100 * dev, e0,
          rho * v0 ** 2 * L / 4 * height)]
print("\n".join(lines))
fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
axes[0].plot(t, u, label="MPM (particle at x = %.3f m)" % x_tip)
axes[0].plot(t, [v0 / omega * math.sin(omega * ti) * math.sin(beta * x_tip) for ti in t], "k--", lw=1, label="analytic")
axes[0].set_ylabel("u [m]")
for col in ("kinetic", "strain", "total"):
    axes[1].plot(t, p[col], label=col)
axes[1].set_ylabel("energy [J/m]")
axes[1].set_xlabel("t [s]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_title("vibrating bar: " + lines[0], fontsize=8)
save(fig, out)
