"""Turek & Hron (2006) FSI1: the drag and the lift of the cylinder with its elastic flag and the displacement of the
flag's tip (point A), time means over the last 16 s of the run (the benchmark's flow and flag are steady at Re = 20;
the means remove the remeshing's noise on the forces and the flag's slow swing), against the benchmark's values
(reference/turek_hron_2006_fsi1.csv).
Records: drag, lift (N/m: the cylinder's wall force and the coupling's interface force added), ux_A, uy_A (m), their
standard deviations over the window (drag_std, lift_std, uy_std), drag_cylinder (the cylinder's share), discharge
(the flow rate at x = 1.5 m over the inflow's 0.082 m^2/s, same window), iterations (coupling passes per step, mean
over the run).
Usage: /usr/bin/python3 cases/turek_hron_fsi1/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, water_balance
from turek_hron import reference, total_forces, window_stats

out = out_dir_from_argv("out/turek_hron_fsi1")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
WINDOW = 16.0  # s, the averaging window at the end of the run (the flag swings slowly, by about 0.1 mm over 2-3 s)
Q_IN = 0.2 * 0.41  # the inflow's flow rate

ref = {k: v[0] for k, v in reference(here, "FSI1").items()}
p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
drag, lift = total_forces(p)
ux, uy = p["tip_ux"], p["tip_uy"]
t0, mean, std = window_stats(t, WINDOW)
steps = [k for k in range(len(t)) if p["fsi_iterations"][k] > 0]

values = {"drag": mean(drag), "lift": mean(lift), "ux_A": mean(ux), "uy_A": mean(uy),
          "drag_std": std(drag), "lift_std": std(lift), "uy_std": std(uy),
          "drag_cylinder": mean(p["drag_cylinder"]), "discharge": mean(p["discharge"]) / Q_IN,
          "iterations": sum(p["fsi_iterations"][k] for k in steps) / max(1, len(steps)),
          "balance": water_balance(out)}
for k, v in values.items():
    record(k, v)


def err(name):
    return 100 * (values[name] / ref[name] - 1)


print("%s: drag %.3f N/m (reference %.3f, %+.2f %%, std %.2f), lift %.3f N/m (reference %.4f, %+.1f %%, std %.2f); "
      "ux_A %.3e m (reference %.4e, %+.0f %%), uy_A %.3e m (reference %.4e, %+.1f %%, std %.1e); cylinder's drag %.3f; "
      "flow rate %.4f of the inflow's; %.2f coupling passes per step; means over %.1f-%.1f s"
      % (tag, values["drag"], ref["drag"], err("drag"), values["drag_std"], values["lift"], ref["lift"], err("lift"),
         values["lift_std"], values["ux_A"], ref["ux_A"], err("ux_A"), values["uy_A"], ref["uy_A"], err("uy_A"),
         values["uy_std"], values["drag_cylinder"], values["discharge"], values["iterations"], t0, t[-1]))

# a running mean over 0.5 s shows the trend under the remeshing's noise
n = max(1, int(round(0.5 / (t[1] - t[0])))) if len(t) > 1 else 1


def running(v):
    return [sum(v[max(0, k - n + 1):k + 1]) / len(v[max(0, k - n + 1):k + 1]) for k in range(len(v))]


fig, axes = plt.subplots(2, 2, figsize=(12, 7))
for ax, v, name, scale, unit in ((axes[0][0], drag, "drag", 1, "N/m"), (axes[0][1], lift, "lift", 1, "N/m"),
                                 (axes[1][0], ux, "ux_A", 1e3, "mm"), (axes[1][1], uy, "uy_A", 1e3, "mm")):
    ax.plot(t, [scale * x for x in v], lw=0.6, color="0.6", label="lagfsi, each step")
    ax.plot(t, [scale * x for x in running(v)], lw=1.2, label="lagfsi, mean over 0.5 s")
    ax.axhline(scale * ref[name], color="k", ls="--", label="Turek & Hron (2006) FSI1: %.4g %s" % (scale * ref[name], unit))
    ax.axvspan(t0, t[-1], color="0.9", zorder=0)
    if name == "drag":
        ax.set_ylim(0.5 * ref[name], 1.5 * ref[name])
    elif name == "lift":
        ax.set_ylim(ref[name] - 4.0, ref[name] + 4.0)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("%s [%s]" % (name, unit))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("turek_hron_fsi1 (%s): drag %.3f (%+.1f %%), lift %.3f, uy_A %.3f mm (%+.1f %%), ux_A %.4f mm"
             % (tag, values["drag"], err("drag"), values["lift"], 1e3 * values["uy_A"], err("uy_A"),
                1e3 * values["ux_A"]))
fig.tight_layout()
save(fig, out, "comparison_%s.png" % tag)
