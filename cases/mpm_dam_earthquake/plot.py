"""Earth dam under an earthquake (MPM, Ludeña 2016 ch. 4): crest acceleration and displacement histories, the
base motion, and the permanent horizontal displacements caused by the earthquake alone (at the end minus at the
end of the static phase, t = 20 s) of the crest and the downstream slope points, against the thesis's
Makdisi-Seed estimates (0.11-0.62 m for sliding masses from the crest down to the full height); the
permanent values are means over the free vibration minus means over the end of the static phase.
Usage: /usr/bin/python3 cases/mpm_dam_earthquake/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, interp

out = out_dir_from_argv("out/mpm_dam_earthquake")
p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
t_static, t_eq_end = 20.0, 80.0
rel = lambda col: [u - b for u, b in zip(p[col], p["base_ux"])]  # relative to the foundation's base
lines = []
crest_rel = rel("crest_ux")
def mean_over(values, a, b):
    sel = [v for ti, v in zip(t, values) if a <= ti <= b]
    return sum(sel) / len(sel)


# The dam still sways after the shaking (period about 3.5 s, little damping): the permanent displacement is the
# mean over the free vibration (80-90 s) minus the mean over the end of the static phase (15-20 s).
perm = {col: mean_over(rel(col), t_eq_end, t[-1]) - mean_over(rel(col), t_static - 5, t_static)
        for col in ("crest_ux", "slope_h34_ux", "slope_h12_ux", "slope_h14_ux")}
record("static_settlement", -interp(t_static, t, p["crest_uy"]))
record("amplification", max(abs(a) for a in p["crest_ax"]) / max(abs(a) for a in p["base_ax"]))
record("peak_crest_acceleration", max(abs(a) for a in p["crest_ax"]))
for col in perm:
    record("permanent_" + col, perm[col])
lines.append("static crest settlement %.2f m; peak base acceleration %.2f m/s^2, peak crest acceleration %.2f m/s^2 "
             "(amplification %.2f)" % (-interp(t_static, t, p["crest_uy"]), max(abs(a) for a in p["base_ax"]),
                                      max(abs(a) for a in p["crest_ax"]),
                                      max(abs(a) for a in p["crest_ax"]) / max(abs(a) for a in p["base_ax"])))
lines.append("permanent horizontal displacement from the earthquake (downstream positive): crest %.3f m, slope at "
             "3H/4 %.3f m, H/2 %.3f m, H/4 %.3f m; Makdisi-Seed (thesis) 0.11-0.62 m; crest settlement from the "
             "earthquake %.3f m" % (perm["crest_ux"], perm["slope_h34_ux"], perm["slope_h12_ux"], perm["slope_h14_ux"],
                                    mean_over(p["crest_uy"], t_static - 5, t_static) - mean_over(p["crest_uy"], t_eq_end, t[-1])))
print("\n".join(lines))
fig, axes = plt.subplots(3, 1, figsize=(11, 8), sharex=True)
axes[0].plot(t, p["base_ax"], lw=0.6, label="base (foundation particle)")
axes[0].plot(t, p["crest_ax"], lw=0.6, label="crest")
axes[0].set_ylabel("a_x [m/s^2]")
axes[1].plot(t, crest_rel, label="crest u_x relative to the base")
for col in ("slope_h34_ux", "slope_h12_ux", "slope_h14_ux"):
    axes[1].plot(t, rel(col), lw=0.8, label=col)
axes[1].set_ylabel("u_x [m]")
axes[2].plot(t, p["crest_uy"], label="crest u_y")
axes[2].set_ylabel("u_y [m]")
axes[2].set_xlabel("t [s]")
for ax in axes:
    ax.axvspan(t_static, t_eq_end, color="0.9", zorder=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
axes[0].set_title("dam: " + lines[0], fontsize=7)
save(fig, out)
