"""The remeshed twins of the free sloshing case (case_remesh.json, case_advected.json): per period, the largest
kinetic energy and the wave's energy at the period's end (KE + PE above the flat surface of the same area,
PE = -rho int g.x dA over the mesh), the area drift, and what remeshing changed (log.csv remesh_dA, remesh_dKE).
Usage: /usr/bin/python3 cases/sloshing_free/plot_twin.py OUTDIR [OUTDIR2 ...]  (writes OUTDIR/twin.png)"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

T1, rho, g, L = 1.18182, 1000.0, 9.81, 1.0
outs = sys.argv[1:] or ["out/sloshing_free_remesh"]
fig, axes = plt.subplots(1, 2, figsize=(12, 3.8))
for k, out in enumerate(outs):
    p = read_csv(os.path.join(out, "probes.csv"))
    log = read_csv(os.path.join(out, "log.csv"))
    t, A, KE, PE = p["time"], p["fluid_area"], p["kinetic_energy"], p["potential_energy"]
    wave = [ke + pe - rho * g * a * a / (2 * L) for ke, pe, a in zip(KE, PE, A)]
    periods = int(t[-1] / T1 + 1e-6)
    rows = []
    for n in range(periods):
        idx = [i for i, ti in enumerate(t) if n * T1 < ti <= (n + 1) * T1 + 1e-9]
        rows.append((n + 1, max(KE[i] for i in idx), wave[idx[-1]]))
    drift = [a / A[0] - 1 for a in A]
    with open(os.path.join(out, "summary.json")) as f:
        rem = json.load(f)["bodies"][0].get("remeshing", {})
    print("%s: %d periods; area drift at the end %+.4f %% (max |drift| %.4f %%); wave energy %.4f J/m at the start"
          % (out, periods, 100 * drift[-1], 100 * max(abs(d) for d in drift), wave[0]))
    print("  period  largest KE  wave energy at its end")
    for r in rows:
        print("  %6d  %10.4f  %10.4f" % r)
    print("  remeshing: area changed %+.3e m^2 in all (sum |dA| %.3e); kinetic energy changed %+.4f J/m in all"
          % (sum(log["remesh_dA"]), sum(abs(x) for x in log["remesh_dA"]), sum(log["remesh_dKE"])))
    if k == 0:
        record("wave_energy_start", wave[0])
        record("wave_energy_end", rows[-1][2])
        record("wave_energy_ratio", rows[-1][2] / wave[0])
        record("ke_max", max(r[1] for r in rows))
        record("area_drift_end", drift[-1])
        record("area_drift_max", max(abs(d) for d in drift))
        record("remesh_ke_change", sum(log["remesh_dKE"]))
    axes[0].plot([r[0] for r in rows], [r[2] for r in rows], "o-", label=os.path.basename(os.path.normpath(out)))
    axes[1].plot(t, [100 * d for d in drift], label=os.path.basename(os.path.normpath(out)))
axes[0].set_xlabel("period")
axes[0].set_ylabel("wave energy at the period's end [J/m]")
axes[1].set_xlabel("t [s]")
axes[1].set_ylabel("area drift [%]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
save(fig, outs[0], "twin.png")
