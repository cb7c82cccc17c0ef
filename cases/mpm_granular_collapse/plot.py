"""Granular column collapse (Bui et al. 2008): the final deposit of the MPM particles against the experimental
free surface (reference/bui2008_final_free_surface.csv). Reads OUTDIR/bars_particles.csv (the particles at the last
output). The simulated surface at an experimental x is the highest particle within half a particle spacing of it,
plus half a spacing. Prints the RMS error of the surface over the experiment's points, where the deposit becomes
thinner than 5 mm, and the run time.
Usage: /usr/bin/python3 cases/mpm_granular_collapse/plot.py OUTDIR"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/mpm_granular_collapse")
c = read_csv(os.path.join(out, "bars_particles.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "bui2008_final_free_surface.csv"))
with open(os.path.join(out, "resolved_case.json")) as f:
    body = json.load(f)["bodies"][0]
hp = body["grid"]["cell"] / body["particles_per_cell"]
x, y = c["x"], c["y"]


def surface(xr):
    tops = [yy for xx, yy in zip(x, y) if abs(xx - xr) <= hp]
    return max(tops) + hp / 2 if tops else 0.0


sim = [surface(xr) for xr in ref["x_m"]]
rms = math.sqrt(sum((s - z) ** 2 for s, z in zip(sim, ref["z_m"])) / len(sim))
thick = [b * 0.005 for b in range(160) if surface(b * 0.005 + 0.0025) >= 0.005]
# Where the measured surface drops below 5 mm (linear interpolation between the digitized points).
exp_end = next(x0 + (x1 - x0) * (z0 - 0.005) / (z0 - z1)
               for x0, z0, x1, z1 in zip(ref["x_m"], ref["z_m"], ref["x_m"][1:], ref["z_m"][1:]) if z0 >= 0.005 > z1)
with open(os.path.join(out, "summary.json")) as f:
    s = json.load(f)
record("surface_rms", rms)
record("deposit_end", max(thick) + 0.005)
record("last_particle", max(x))
lines = ["final free surface RMS error %.2f mm over %d experimental points; deposit >= 5 mm thick to x = %.3f m "
         "(experiment: %.3f m); last particle at %.3f m; %.1f s (%d threads)" %
         (1e3 * rms, len(sim), max(thick) + 0.005, exp_end, max(x), s["wall_time"], s["threads"])]
print("\n".join(lines))
fig, ax = plt.subplots(figsize=(11, 4))
ax.scatter(x, y, s=0.5, c=c["syy"], cmap="viridis", label="MPM particles (colour: sigma_yy)")
ax.plot(ref["x_m"], ref["z_m"], "r-", lw=1.5, label="experiment (Bui et al. 2008)")
ax.plot([0, 0.2, 0.2], [0.1, 0.1, 0], "k:", lw=1, label="initial column")
ax.set_aspect("equal")
ax.set_xlim(0, max(0.5, max(x) + 0.01))
ax.set_ylim(0, 0.11)
ax.set_xlabel("x [m]")
ax.set_ylabel("z [m]")
ax.legend(fontsize=7, loc="upper right")
ax.set_title("granular collapse: " + lines[0], fontsize=7)
save(fig, out)
