"""Mattiasson's elastica with 8 cubic shell elements: tip deflection w/L and shortening u/L against the
elliptic-integral table. Usage: /usr/bin/python3 cases/elastica_shell/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save, interp

out = out_dir_from_argv("out/elastica_shell")
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "mattiasson_1981_cantilever_elastica.csv"))
lam = [10 * t for t in p["time"]]
lines = []
for l, w, u in zip(ref["lambda"], ref["w_over_L"], ref["u_over_L"]):
    wl, ul = interp(l, lam, p["tip_uy"]), -interp(l, lam, p["tip_ux"])
    lines.append("lambda %4.1f: w/L %.5f (table %.5f, %+.3f %%), u/L %.5f (table %.5f, %+.3f %%)" %
                 (l, wl, w, 100 * (wl / w - 1), ul, u, 100 * (ul / u - 1)))
print("\n".join(lines))
fig, ax = plt.subplots(figsize=(7, 4.5))
ax.plot(lam, p["tip_uy"], "-", label="w/L, 8 cubic shell elements")
ax.plot(lam, [-u for u in p["tip_ux"]], "-", label="u/L, 8 cubic shell elements")
ax.plot(ref["lambda"], ref["w_over_L"], "ko", label="Mattiasson (1981)")
ax.plot(ref["lambda"], ref["u_over_L"], "ks")
ax.set_xlabel("lambda = P L^2 / EI")
ax.set_ylabel("tip displacement / L")
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
ax.set_title("elastica, shell: " + lines[-1], fontsize=8)
save(fig, out)
