"""Sloshing of a viscous fluid (Avancini 2018 sec. 6.9.5, after Franci 2016): free-surface elevation next to both walls,
kinetic energy (log scale) and fluid area against time; if the VTK Python module is available, snapshots of
the particles coloured by pressure. Usage: /usr/bin/python3 cases/sloshing_viscous/plot.py OUTDIR"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, read_particle_snapshots, plot_particle_snapshots

out = out_dir_from_argv("out/sloshing_viscous")
p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
a0 = p["fluid_area"][0]
drift = [100 * (x / a0 - 1) for x in p["fluid_area"]]
ke = p["kinetic_energy"]
kmax = max(ke)
wall = float("nan")
try:
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
        wall, status = s["wall_time"], s["status"]
except (OSError, KeyError, ValueError):
    status = "?"
record("t_end", t[-1])
record("area_drift_max", max(abs(d) for d in drift) / 100)
record("kinetic_energy_peak", kmax)
record("kinetic_energy_final", ke[-1])
record("eta_left_end", p["eta_left"][-1])
tail = [k for tt, k in zip(t, ke) if tt >= t[-1] - 0.5]
print("%s to t = %.3f s in %.0f s of wall time; area drift at the end %+.3f %%, max |drift| %.3f %%; kinetic "
      "energy: peak %.3f J, mean over the last 0.5 s %.3e J (%.1e of the peak), final %.3e J; elevation left/right "
      "at the end %.4f / %.4f m (level 0.25)" % (status, t[-1], wall, drift[-1], max(abs(d) for d in drift), kmax,
                                                 sum(tail) / len(tail), sum(tail) / len(tail) / kmax, ke[-1],
                                                 p["eta_left"][-1], p["eta_right"][-1]))

# First-mode period from the maxima of the elevation next to the left wall (after the release transient,
# while the amplitude is above 2 mm), against linear inviscid theory omega^2 = g k tanh(k d), k = pi/L.
L, d, g = 0.5, 0.25, 9.81
k1 = math.pi / L
T_lin = 2 * math.pi / math.sqrt(g * k1 * math.tanh(k1 * d))
e = p["eta_left"]
peaks = []
for i in range(1, len(e) - 1):
    if t[i] > 0.5 and e[i] >= e[i - 1] and e[i] > e[i + 1] and e[i] > d + 0.002:
        if peaks and t[i] - peaks[-1] < 0.4:
            continue
        peaks.append(t[i])
period = (peaks[-1] - peaks[0]) / (len(peaks) - 1) if len(peaks) > 1 else float("nan")
record("period", period)
print("first-mode period from %d left-wall maxima: %.3f s; linear theory %.3f s (%+.1f %%)"
      % (len(peaks), period, T_lin, 100 * (period / T_lin - 1)))

snaps = read_particle_snapshots(out, "fluid.pvd", [0.0, 0.2, 0.4, 0.6, 1.0, t[-1]], 0.05)

fig = plt.figure(figsize=(16, 8 if snaps else 4.2))
rows = 2 if snaps else 1
ax = fig.add_subplot(rows, 3, 1)
ax.plot(t, p["eta_left"], label="next to the left wall (x = 0.015)")
ax.plot(t, p["eta_right"], label="next to the right wall (x = 0.485)")
ax.axhline(0.25, color="k", ls=":", lw=1, label="level at rest 0.25 m")
ax.set_xlabel("t [s]")
ax.set_ylabel("free-surface elevation [m]")
ax.set_title("period %.3f s (linear theory %.3f s)" % (period, T_lin), fontsize=9)
ax.legend(fontsize=7)
ax = fig.add_subplot(rows, 3, 2)
ax.semilogy(t, [max(k, 1e-12) for k in ke])
ax.set_xlabel("t [s]")
ax.set_ylabel("kinetic energy [J/m]")
ax = fig.add_subplot(rows, 3, 3)
ax.plot(t, drift)
ax.axhline(1, color="r", ls=":", lw=1)
ax.axhline(-1, color="r", ls=":", lw=1)
ax.set_xlabel("t [s]")
ax.set_ylabel("fluid area drift [%]")
for a in fig.axes:
    a.grid(alpha=0.3)
plot_particle_snapshots(fig, snaps, (-0.01, 0.51), (-0.01, 0.51), 3500)
save(fig, out)
