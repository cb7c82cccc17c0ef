"""Saturated square (two-phase MPM, Ludeña 2016 sec. 3.6): pore pressure of the control particles over time and the
final profile against hydrostatic gamma_w depth. The pressure is uniform within each cell (the grid's
velocity divergence is), so it is compared at the cell centres; the base value is extrapolated from the two
lowest cells.
Usage: /usr/bin/python3 cases/mpm_saturated_square/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/mpm_saturated_square")
p = read_csv(os.path.join(out, "probes.csv"))
c = read_csv(os.path.join(out, "square_particles.csv"))
gw, h, H = 1019.37 * 9.81, 0.1, 1.0
rows = {}
for y, pw in zip(c["Y"], c["pore_pressure"]):
    rows.setdefault(int(y // h), []).append(pw)
centres = sorted(rows)
pc = [sum(rows[r]) / len(rows[r]) for r in centres]
yc = [(r + 0.5) * h for r in centres]
err = max(abs(a - gw * (H - y)) for a, y in zip(pc, yc)) / (gw * H)
base = pc[0] + (pc[0] - pc[1]) / 2
record("cell_centre_error", err)
record("base_extrapolated", base)
record("base_particle", p["p_base"][-1])
lines = ["cell-centre pore pressure within %.2f %% of gamma_w H of hydrostatic; base (extrapolated) %.0f Pa "
         "(hydrostatic %.0f Pa); base control particle (second row) %.0f Pa" % (100 * err, base, gw * H, p["p_base"][-1])]
print("\n".join(lines))
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
for col in ("p_base", "p_middle", "p_top"):
    axes[0].plot(p["time"], [v / 1e3 for v in p[col]], label=col)
axes[0].set_xlabel("t [s]")
axes[0].set_ylabel("pore pressure [kPa]")
axes[1].plot([v / 1e3 for v in c["pore_pressure"]], c["Y"], "o", ms=2, label="particles")
axes[1].plot([gw * (H - y) / 1e3 for y in (0, H)], [0, H], "k--", lw=1, label="hydrostatic")
axes[1].set_xlabel("pore pressure [kPa]")
axes[1].set_ylabel("y [m]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("saturated square: " + lines[0], fontsize=7)
save(fig, out)
