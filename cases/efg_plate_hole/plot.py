"""EFG plate with a hole against Kirsch: sigma_xx at the top of the hole (3 sigma0) and sigma_yy at its side (-sigma0),
and the stress along x = 0 from the integration-point cloud if ParaView output exists (not needed for the numbers).
Usage: /usr/bin/python3 cases/efg_plate_hole/plot.py OUTDIR"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/efg_plate_hole")
p = read_csv(os.path.join(out, "probes.csv"))
s = json.load(open(os.path.join(out, "summary.json")))["bodies"][0]
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "efg_plate_hole_kirsch.csv"))
sA, sB = p["sxx_A"][-1], p["syy_B"][-1]
print("sigma_xx(0, 1) = %.4f (Kirsch 3, %+.2f %%); sigma_yy(1, 0) = %.4f (Kirsch -1, %+.2f %%); relative energy error %.4e"
      % (sA, 100 * (sA / 3 - 1), sB, 100 * (-sB - 1), s["energy_error_relative"]))
fig, ax = plt.subplots(figsize=(6, 4))
y = [r for r, l in zip(ref["r"], ref["line"]) if l == "along_y_axis_theta90"]
sx = [v for v, l in zip(ref["sigma_xx"], ref["line"]) if l == "along_y_axis_theta90"]
ax.plot(y, sx, "k-", label="Kirsch sigma_xx on x = 0")
ax.plot([1.0], [sA], "ro", label="EFG sigma_xx(0, 1)")
ax.set_xlabel("y")
ax.set_ylabel("sigma_xx / sigma0")
ax.legend()
ax.grid(alpha=0.3)
save(fig, out)
