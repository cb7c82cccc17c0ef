"""Tip displacements of the cantilever strip against Mattiasson's elastica table.
Usage: /usr/bin/python3 cases/elastica_mattiasson/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/elastica_mattiasson")
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "mattiasson_1981_cantilever_elastica.csv"))
p = read_csv(os.path.join(out, "probes.csv"))
lam = [10 * t for t in p["time"]]
L = 1.0
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(lam, [u / L for u in p["tip_uy"]], "-", label="lagfsi w/L")
ax.plot(lam, [-u / L for u in p["tip_ux"]], "-", label="lagfsi u/L")
ax.plot(ref["lambda"], ref["w_over_L"], "ko", mfc="none", label="Mattiasson (1981) w/L")
ax.plot(ref["lambda"], ref["u_over_L"], "ks", mfc="none", label="Mattiasson (1981) u/L")
for lr, w, u in zip(ref["lambda"], ref["w_over_L"], ref["u_over_L"]):
    i = min(range(len(lam)), key=lambda k: abs(lam[k] - lr))
    print("lambda %4.1f  w/L %.5f (ref %.5f, %+.2f %%)  u/L %.5f (ref %.5f, %+.2f %%)" % (
        lr, p["tip_uy"][i] / L, w, 100 * (p["tip_uy"][i] / L / w - 1), -p["tip_ux"][i] / L, u,
        100 * (-p["tip_ux"][i] / L / u - 1)))
ax.set_xlabel("lambda = P L^2 / EI")
ax.set_ylabel("tip displacement / L")
ax.set_title("Cantilever elastica under a dead tip load")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
