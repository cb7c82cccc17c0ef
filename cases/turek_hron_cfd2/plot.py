"""Turek & Hron (2006) CFD2: the drag and the lift of the rigid cylinder with its flag, time means over the last
1 s of the run (the flow is steady at Re = 100; the means remove the noise of the remeshing), against the
benchmark's values (reference/turek_hron_2006_cfd2.csv). Records: drag, lift (N/m: the cylinder's and the flag's
forces added), drag_std, lift_std (their standard deviations over the window), drag_cylinder, lift_cylinder (the
cylinder's share), discharge (the flow rate at x = 1.5 m over the inflow's 0.41 m^2/s, same window).
Usage: /usr/bin/python3 cases/turek_hron_cfd2/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/turek_hron_cfd2")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
WINDOW = 1.0  # s, the averaging window at the end of the run
Q_IN = 1.0 * 0.41  # the inflow's flow rate

ref = {}
with open(os.path.join(here, "reference", "turek_hron_2006_cfd2.csv")) as f:
    for line in f:
        if line.startswith("CFD2,"):
            c = line.split(",")
            ref[c[1]] = float(c[2])

p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
drag = [a + b for a, b in zip(p["drag_cylinder"], p["drag_flag"])]
lift = [a + b for a, b in zip(p["lift_cylinder"], p["lift_flag"])]
t0 = t[-1] - WINDOW
late = [k for k, tk in enumerate(t) if tk >= t0 - 1e-9]


def mean(v):
    return sum(v[k] for k in late) / len(late)


def std(v):
    m = mean(v)
    return math.sqrt(sum((v[k] - m) ** 2 for k in late) / len(late))


values = {"drag": mean(drag), "lift": mean(lift), "drag_std": std(drag), "lift_std": std(lift),
          "drag_cylinder": mean(p["drag_cylinder"]), "lift_cylinder": mean(p["lift_cylinder"]),
          "discharge": mean(p["discharge"]) / Q_IN}
for k, v in values.items():
    record(k, v)
print("%s: drag %.3f N/m (reference %.2f, %+.2f %%, std %.2f), lift %.3f N/m (reference %.3f, %+.1f %%, std %.2f); "
      "cylinder %.3f / %.3f; flow rate %.4f of the inflow's; means over %.1f-%.1f s"
      % (tag, values["drag"], ref["drag"], 100 * (values["drag"] / ref["drag"] - 1), values["drag_std"],
         values["lift"], ref["lift"], 100 * (values["lift"] / ref["lift"] - 1), values["lift_std"],
         values["drag_cylinder"], values["lift_cylinder"], values["discharge"], t0, t[-1]))

fig, axes = plt.subplots(1, 2, figsize=(12, 3.8))
for ax, v, name in ((axes[0], drag, "drag"), (axes[1], lift, "lift")):
    ax.plot(t, v, lw=0.6, color="0.6", label="lagfsi, each step")
    # a running mean over 0.5 s shows the trend under the remeshing's noise
    n = max(1, int(round(0.5 / (t[1] - t[0])))) if len(t) > 1 else 1
    run = [sum(v[max(0, k - n + 1):k + 1]) / len(v[max(0, k - n + 1):k + 1]) for k in range(len(v))]
    ax.plot(t, run, lw=1.2, label="lagfsi, mean over 0.5 s")
    ax.axhline(ref[name], color="k", ls="--", label="Turek & Hron (2006) CFD2: %.4g" % ref[name])
    ax.axvspan(t0, t[-1], color="0.9", zorder=0)
    lo = ref[name] - (0.5 * ref[name] if name == "drag" else 20.0)
    hi = ref[name] + (0.5 * ref[name] if name == "drag" else 20.0)
    ax.set_ylim(lo, hi)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("%s [N/m]" % name)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("turek_hron_cfd2 (%s): drag %.3f (%+.1f %%), lift %.3f" % (tag, values["drag"],
             100 * (values["drag"] / ref["drag"] - 1), values["lift"]))
save(fig, out, "comparison_%s.png" % tag)
