"""Elastic gate (Antoci, Gallati & Sibilla 2007): displacement of the gate's free end against the experiment
(reference/antoci_2007_experiment_tip_displacement.csv) and three published numerical solutions
(reference/antoci_gate_numerical_tip_displacement.csv). Prints the RMS error of each component over the
points of each series and the coupling statistics.
Usage: /usr/bin/python3 cases/elastic_gate_antoci/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, coupling_lines, rms_against, antoci_solutions, ANTOCI_SOLUTIONS

out = out_dir_from_argv("out/elastic_gate_antoci")
p = read_csv(os.path.join(out, "probes.csv"))
here = os.path.join(os.path.dirname(__file__), "reference")
ref = read_csv(os.path.join(here, "antoci_2007_experiment_tip_displacement.csv"))
t = p["time"]
lines = []
series = {}
numerical = antoci_solutions(here, t[-1])
# The published solutions report the end's downstream corner (x = 0.105 m at rest): probes tip_right_*; tip_* is
# the upstream corner (x = 0.1 m). The two differ by t sin(theta) ~ 3 mm in y once the end has turned.
RIGHT = {"x": "tip_right_ux", "y": "tip_right_uy"}

for comp, col in (("x", "tip_ux"), ("y", "tip_uy")):
    pts = [(tr, ur) for c, tr, ur in zip(ref["component"], ref["time"], ref["displacement"]) if c == comp and tr <= t[-1]]
    series[comp] = pts
    record(col + "_rms_experiment", rms_against(t, p[col], pts))
    lines.append("%s: RMS error %.1f mm over %d experimental points (largest measured %.1f mm)" %
                 (col, 1e3 * rms_against(t, p[col], pts), len(pts), 1e3 * max(abs(u) for _, u in pts)))
    ncol = RIGHT[comp] if RIGHT[comp] in p else col
    if ncol != col:
        lines.append("%s (downstream corner): RMS error %.1f mm over the experimental points" %
                     (ncol, 1e3 * rms_against(t, p[ncol], pts)))
    for src, _ in ANTOCI_SOLUTIONS:
        record("%s_rms_%s" % (ncol, src), rms_against(t, p[ncol], numerical[(src, comp)]))
    errs = ["%s %.1f" % (src, 1e3 * rms_against(t, p[ncol], numerical[(src, comp)])) for src, _ in ANTOCI_SOLUTIONS]
    lines.append("%s: RMS difference from the published solutions [mm]: %s" % (ncol, ", ".join(errs)))
lines += coupling_lines(out)
print("\n".join(lines))

fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
for ax, comp, col in zip(axes, ("x", "y"), ("tip_ux", "tip_uy")):
    ax.plot(t, [1e3 * u for u in p[col]], label="lagfsi, upstream corner", lw=2)
    if RIGHT[comp] in p:
        ax.plot(t, [1e3 * u for u in p[RIGHT[comp]]], color="C0", ls="--", lw=1.5, label="lagfsi, downstream corner")
    for (src, name), style in zip(ANTOCI_SOLUTIONS, (":", "--", "-.")):
        pts = numerical[(src, comp)]
        ax.plot([a for a, _ in pts], [1e3 * b for _, b in pts], style, color="gray", lw=1, label=name)
    ax.plot([a for a, _ in series[comp]], [1e3 * b for _, b in series[comp]], "ko", ms=4,
            label="Antoci et al. 2007 (experiment)")
    ax.set_ylabel("free end %s [mm]" % col)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[1].set_xlabel("t [s]")
axes[0].set_title("elastic gate: " + lines[0], fontsize=9)
save(fig, out)
