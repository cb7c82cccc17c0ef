"""Shaken tank: wall elevations against the linear modal solution (reference/linear_modal_solution.csv).
Prints the RMS error over 0-3 s and over the whole run, relative to the largest linear elevation.
Usage: /usr/bin/python3 cases/sloshing_forced/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, particle_steps, save

out = out_dir_from_argv("out/sloshing_forced")
d = 0.5
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "linear_modal_solution.csv"))


def interp(x, xs, ys):
    i = min(max(int(x / (xs[1] - xs[0])), 0), len(xs) - 2)
    s = (x - xs[i]) / (xs[i + 1] - xs[i])
    return ys[i] + s * (ys[i + 1] - ys[i])


def rel_rms(col, t_end):
    e2, n, peak = 0.0, 0, 0.0
    for t, v in zip(p["time"], p[col]):
        if t > t_end or math.isnan(v):
            continue
        lin = interp(t, ref["time"], ref[col])
        e2 += (v - d - lin) ** 2
        n += 1
    peak = max(abs(v) for t, v in zip(ref["time"], ref[col]) if t <= t_end)
    return math.sqrt(e2 / n) / peak, peak


t_end = p["time"][-1]
lines = []
for col in ("eta_left", "eta_right"):
    r3, pk3 = rel_rms(col, min(3.0, t_end))
    ra, pka = rel_rms(col, t_end)
    record(col + "_rms_3s", r3)
    record(col + "_rms_end", ra)
    lines.append("%s: RMS error / linear peak %.3f over 0-3 s (peak %.1f mm), %.3f over 0-%.1f s" %
                 (col, r3, 1e3 * pk3, ra, t_end))
a0 = p["fluid_area"][0]
record("particle_steps", particle_steps(out))
record("area_drift_max", max(abs(a / a0 - 1) for a in p["fluid_area"]))
lines.append("area drift at the end %+.3f %% (max |drift| %.3f %%)" %
             (100 * (p["fluid_area"][-1] / a0 - 1), max(abs(100 * (a / a0 - 1)) for a in p["fluid_area"])))
print("\n".join(lines))

fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
for ax, col, name in zip(axes, ("eta_left", "eta_right"), ("x = 0.05 m", "x = 0.95 m")):
    ax.plot(p["time"], [1e3 * (v - d) for v in p[col]], label="lagfsi (PFEM)")
    ax.plot(ref["time"], [1e3 * v for v in ref[col]], "k--", lw=1, label="linear modal theory")
    ax.set_ylabel("elevation at %s [mm]" % name)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_title("shaken tank: " + lines[0])
axes[1].set_xlabel("t [s]")
save(fig, out)
