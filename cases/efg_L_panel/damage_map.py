"""Damage at the integration points of EFG L-panel runs (the .vtp point clouds), last written step of each run.
Usage: /usr/bin/python3 cases/efg_L_panel/damage_map.py OUT_PNG OUTDIR [OUTDIR2 ...]"""
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import vtk
from vtk.util.numpy_support import vtk_to_numpy

png, outs = sys.argv[1], sys.argv[2:]
fig, axes = plt.subplots(1, len(outs), figsize=(4.2 * len(outs), 4), squeeze=False)
for ax, o in zip(axes[0], outs):
    files = sorted(glob.glob(os.path.join(o, "panel_gauss", "*.vtp")))
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(files[-1])
    r.Update()
    d = r.GetOutput()
    pts = vtk_to_numpy(d.GetPoints().GetData())
    dmg = vtk_to_numpy(d.GetPointData().GetArray("damage"))
    sc = ax.scatter(pts[:, 0], pts[:, 1], c=dmg, s=2, cmap="jet", vmin=0, vmax=1)
    ax.set_aspect("equal")
    ax.set_title(os.path.basename(o.rstrip("/")), fontsize=9)
    print("%s: %s, %d points, damage > 0.9 at %d" % (o, os.path.basename(files[-1]), len(dmg), int((dmg > 0.9).sum())))
fig.colorbar(sc, ax=axes[0].tolist(), shrink=0.8, label="damage")
fig.savefig(png, dpi=120)
print("wrote", png)
