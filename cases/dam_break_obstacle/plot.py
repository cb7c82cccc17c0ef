"""Dam break with a rigid obstacle (Koshizuka, Tamako & Oka 1995; Avancini 2018 sec. 6.9.4): reach of the jet
(largest x of connected fluid) and floor front against time, with the time the jet reaches the right wall;
pressures on the right wall and on the obstacle's upstream face; fluid area; and, if the VTK Python module is
available, snapshots at 0.1-0.5 s (Avancini 2018, Figs. 39-43).
Usage: /usr/bin/python3 cases/dam_break_obstacle/plot.py OUTDIR"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, read_particle_snapshots, plot_particle_snapshots

out = out_dir_from_argv("out/dam_break_obstacle")
W, h = 0.584, 0.0073
p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
hit = next((tt for tt, x in zip(t, p["reach_x"]) if x >= W - 1.5 * h), float("nan"))
wet = next((tt for tt, x in zip(t, p["p_right_wall"]) if x != 0.0), float("nan"))
a0 = p["fluid_area"][0]
drift = [100 * (x / a0 - 1) for x in p["fluid_area"]]
i03 = next(i for i, tt in enumerate(t) if tt >= min(0.3, t[-1]))
record("t_end", t[-1])
record("jet_at_wall", hit)
record("wall_wet", wet)
record("area_drift_end", drift[-1] / 100)
record("area_drift_max", max(abs(d) for d in drift) / 100)
try:  # the steps retried with dt / 2, and with "volume_correction": "particle" the water (mesh + drops in flight)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    record("step_retries", summary["step_retries"])
    fa = summary["bodies"][0]["fluid_area"]
    if "water_drift_max" in fa:
        record("water_drift_max", fa["water_drift_max"])
        print("particle volumes: largest water drift %.3f %%" % (100 * fa["water_drift_max"]))
except (OSError, KeyError, ValueError):
    pass
print("ran to t = %.3f s; jet reaches the right wall (largest x >= W - 1.5 h) at %.4f s; right-wall pressure "
      "first non-zero at %.4f s (issue: 0.30-0.35 s); area drift at 0.3 s %+.2f %%, at the end %+.2f %%, "
      "max |drift| %.2f %%" % (t[-1], hit, wet, drift[i03], drift[-1], max(abs(d) for d in drift)))

snaps = read_particle_snapshots(out, "water.pvd", [0.1, 0.2, 0.3, 0.4, 0.5], 0.02)

fig = plt.figure(figsize=(16, 8.5 if snaps else 4.2))
rows = 2 if snaps else 1
ax = fig.add_subplot(rows, 3, 1)
ax.plot(t, p["reach_x"], label="largest x of connected fluid (jet)")
ax.plot(t, p["front_x"], label="front within 2h of the floor")
ax.axhline(W - 1.5 * h, color="k", ls=":", lw=1, label="right wall - 1.5 h")
ax.axvspan(0.30, 0.35, color="g", alpha=0.15, label="issue: jet at the wall 0.30-0.35 s")
ax.axhspan(0.280, 0.304, color="0.8", label="obstacle")
ax.set_xlabel("t [s]")
ax.set_ylabel("x [m]")
ax.set_title("jet at the right wall: %.3f s" % hit)
ax.legend(fontsize=7)
ax = fig.add_subplot(rows, 3, 2)
ax.plot(t, p["p_right_wall"], lw=0.8, label="right wall, y < 0.2 m")
ax.plot(t, p["p_obstacle"], lw=0.8, label="obstacle, upstream face")
ax.set_xlabel("t [s]")
ax.set_ylabel("mean wall pressure [Pa]")
ax.set_ylim(-5000, 20000)
ax.set_title("impact peaks clipped (max %.0f Pa)" % max(p["p_right_wall"] + p["p_obstacle"]), fontsize=9)
ax.legend(fontsize=7)
ax = fig.add_subplot(rows, 3, 3)
ax.plot(t, drift)
ax.set_xlabel("t [s]")
ax.set_ylabel("fluid area drift [%]")
for a in fig.axes:
    a.grid(alpha=0.3)
plot_particle_snapshots(fig, snaps, (-0.01, W + 0.01), (-0.01, 0.45), 3000)
save(fig, out)
