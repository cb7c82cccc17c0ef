"""Elastic gate (Antoci, Gallati & Sibilla 2007) with the gate as shell elements: the free end's displacement
against the experiment, the three published numerical solutions (reference/antoci_gate_numerical_tip_
displacement.csv; they report the end's downstream corner, probes tip_right_*), and the T10 gate
(cases/elastic_gate_antoci) when its output folder is given.
Usage: /usr/bin/python3 cases/elastic_gate_antoci_shell/plot.py OUTDIR [T10_OUTDIR]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
from claims_record import record
from lagfsi_post import (read_csv, out_dir_from_argv, save, shell_vs_continuum, coupling_lines, rms_against,
                         antoci_solutions, ANTOCI_SOLUTIONS)

out = out_dir_from_argv("out/elastic_gate_antoci_shell")
t10 = sys.argv[2] if len(sys.argv) > 2 else "out/elastic_gate_antoci"
p = read_csv(os.path.join(out, "probes.csv"))
here = os.path.join(os.path.dirname(__file__), "reference")
ref = read_csv(os.path.join(here, "antoci_2007_experiment_tip_displacement.csv"))
numerical = antoci_solutions(here, p["time"][-1])
fig, lines = shell_vs_continuum(out, t10, ["tip_ux", "tip_uy"], "")
for ax, comp, col in zip(fig.axes, ("x", "y"), ("tip_ux", "tip_uy")):
    pts = [(tr, ur) for c, tr, ur in zip(ref["component"], ref["time"], ref["displacement"]) if c == comp and tr <= p["time"][-1]]
    record(col + "_rms_experiment", rms_against(p["time"], p[col], pts))
    lines.append("%s: RMS error against the experiment %.1f mm over %d points" %
                 (col, 1e3 * rms_against(p["time"], p[col], pts), len(pts)))
    ncol = col.replace("tip_", "tip_right_") if col.replace("tip_", "tip_right_") in p else col
    for src, _ in ANTOCI_SOLUTIONS:
        record("%s_rms_%s" % (ncol, src), rms_against(p["time"], p[ncol], numerical[(src, comp)]))
    errs = ["%s %.1f" % (src, 1e3 * rms_against(p["time"], p[ncol], numerical[(src, comp)])) for src, _ in ANTOCI_SOLUTIONS]
    lines.append("%s: RMS difference from the published solutions [mm]: %s" % (ncol, ", ".join(errs)))
    ax.plot([a for a, _ in pts], [1e3 * b for _, b in pts], "ko", ms=4, label="Antoci et al. 2007 (experiment)")
    ax.legend(fontsize=8)
fig.axes[0].set_title("elastic gate, 8 cubic shell elements: " + lines[-4], fontsize=9)
lines += coupling_lines(out)
print("\n".join(lines))
save(fig, out)
