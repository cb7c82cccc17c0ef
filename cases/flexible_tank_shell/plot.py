"""Flexible tank (Avancini 2018, sec. 7.3.1) with the wall as shell elements, against the same case with the wall
meshed by T10 elements (cases/flexible_tank) when its output folder is given: tip displacement histories, their largest
difference relative to the peak, and the wall time per body.
Usage: /usr/bin/python3 cases/flexible_tank_shell/plot.py OUTDIR [T10_OUTDIR]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
from lagfsi_post import out_dir_from_argv, save, shell_vs_continuum, coupling_lines

out = out_dir_from_argv("out/flexible_tank_shell")
t10 = sys.argv[2] if len(sys.argv) > 2 else "out/flexible_tank"
fig, lines = shell_vs_continuum(out, t10, ["tip_ux", "tip_uy"], "flexible tank: shell wall against T10 wall")
lines += coupling_lines(out)
print("\n".join(lines))
save(fig, out)
