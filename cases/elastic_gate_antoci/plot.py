"""Elastic gate (Antoci, Gallati & Sibilla 2007): displacement of the gate's free end against the experiment
(reference/antoci_2007_experiment_tip_displacement.csv). Prints the RMS error of each component over the
experiment's points and the coupling statistics.
Usage: /usr/bin/python3 cases/elastic_gate_antoci/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save, coupling_lines, interp

out = out_dir_from_argv("out/elastic_gate_antoci")
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "antoci_2007_experiment_tip_displacement.csv"))
t = p["time"]
lines = []
series = {}
for comp, col in (("x", "tip_ux"), ("y", "tip_uy")):
    pts = [(tr, ur) for c, tr, ur in zip(ref["component"], ref["time"], ref["displacement"]) if c == comp and tr <= t[-1]]
    series[comp] = pts
    rms = math.sqrt(sum((interp(tr, t, p[col]) - ur) ** 2 for tr, ur in pts) / len(pts))
    lines.append("%s: RMS error %.1f mm over %d experimental points (largest measured %.1f mm)" %
                 (col, 1e3 * rms, len(pts), 1e3 * max(abs(u) for _, u in pts)))
lines += coupling_lines(out)
print("\n".join(lines))

fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
for ax, comp, col in zip(axes, ("x", "y"), ("tip_ux", "tip_uy")):
    ax.plot(t, [1e3 * u for u in p[col]], label="lagfsi")
    ax.plot([a for a, _ in series[comp]], [1e3 * b for _, b in series[comp]], "ko", ms=4,
            label="Antoci et al. 2007 (experiment)")
    ax.set_ylabel("free end %s [mm]" % col)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[1].set_xlabel("t [s]")
axes[0].set_title("elastic gate: " + lines[0], fontsize=9)
save(fig, out)
