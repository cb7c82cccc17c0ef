"""Static tip displacement of the Turek-Hron flag under gravity (CSM1) against the benchmark values.
Usage: /usr/bin/python3 cases/turek_csm1/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/turek_csm1")
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "turek_hron_2006_reference_values.csv"))
rv = {q: m for c, q, m in zip(ref["case"], ref["quantity"], ref["mean"]) if c == "CSM1"}
p = read_csv(os.path.join(out, "probes.csv"))
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(p["time"], p["tip_ux"], "o-", label="lagfsi u_x(A)")
ax.plot(p["time"], p["tip_uy"], "s-", label="lagfsi u_y(A)")
ax.plot([1], [rv["ux_A"]], "k*", ms=12, label="Turek & Hron (2006) u_x")
ax.plot([1], [rv["uy_A"]], "kX", ms=10, label="Turek & Hron (2006) u_y")
for q, k in (("ux_A", "tip_ux"), ("uy_A", "tip_uy")):
    print("%s: lagfsi %.6e, reference %.6e, error %+.3f %%" % (q, p[k][-1], rv[q], 100 * (p[k][-1] / rv[q] - 1)))
ax.set_xlabel("load factor")
ax.set_ylabel("tip displacement [m]")
ax.set_title("Turek-Hron CSM1 (static, gravity)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
