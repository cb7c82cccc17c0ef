"""Terzaghi consolidation (two-phase MPM): average degree of consolidation U = 1 - mean excess pore pressure / p0
against the series (reference/mpm_terzaghi_average_consolidation.csv), and the settlement of the top particle.
Prints U at Tv = 0.05, 0.197, 0.5, 0.848 with the errors.
Usage: /usr/bin/python3 cases/mpm_consolidation/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, interp

out = out_dir_from_argv("out/mpm_consolidation")
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "mpm_terzaghi_average_consolidation.csv"))
p0, H, E_oed, k, gamma_w = 1.0e4, 1.0, 1.0e7, 1.0e-3, 1000.0 * 9.81
cv = k * E_oed / gamma_w
t = p["time"]
tv = [cv * ti / H ** 2 for ti in t]
U = [1 - pm / p0 for pm in p["p_mean"]]
lines = []
for T in (0.05, 0.197, 0.5, 0.848):
    u, ua = interp(T, tv, U), interp(T, ref["Tv"], ref["U_avg"])
    record("U_%g" % T, u)
    lines.append("Tv = %.3f: U = %.4f (Terzaghi %.4f, %+.2f %%)" % (T, u, ua, 100 * (u / ua - 1)))
print("\n".join(lines))
fig, ax = plt.subplots(figsize=(8, 5))
ax.semilogx(tv[1:], U[1:], label="MPM, U = 1 - mean pore pressure / p0")
ax.semilogx(tv[1:], [-u / (p0 * H / E_oed) for u in p["top_uy"][1:]], ":", label="MPM, top settlement / final")
ax.semilogx(ref["Tv"], ref["U_avg"], "k--", lw=1, label="Terzaghi (series)")
ax.set_xlabel("Tv = c_v t / H^2")
ax.set_ylabel("U")
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
ax.set_title("Terzaghi consolidation: " + "; ".join(lines[1:3]), fontsize=7)
save(fig, out)
