"""Dam break against a wall with pressure sensors (Zhou, De Kat & Buchner 1999; Buchner 2002; Marrone et al. 2011):
the pressure at P1 (y = 0.16 m) and P2 (y = 0.584 m) on the impacted wall in p* = p / (rho g H) against
t* = t sqrt(g / H), with the experiment and the converged delta-SPH reference, and the measures of the issue:
the impact time at P1 (the last time p* < 0.05 before it first exceeds 0.3), the quasi-static plateau (the mean of
p* over 3.5 < t* < 5), the pressure impulse of the first 0.1 s after the impact, the time the run-up wets P2
(p* > 0.05), the run-up's highest point and the largest share of the water above 2 H.
Usage: /usr/bin/python3 cases/dam_break_pressure/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/dam_break_pressure")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
H, g, rho = 0.6, 9.81, 1000.0
ts, ps = math.sqrt(g / H), rho * g * H
IMPULSE_WINDOW = 0.1 * ts  # 0.1 s in t*


def onset(t, p):
    """The last time p < 0.05 before p first exceeds 0.3."""
    k = next(i for i, v in enumerate(p) if v > 0.3)
    return t[max(i for i in range(k) if p[i] < 0.05)]


def impulse(t, p, t0, width):
    """Trapezoidal integral of p over [t0, t0 + width] (linear interpolation at the ends)."""
    total = 0.0
    for i in range(len(t) - 1):
        lo, hi = max(t[i], t0), min(t[i + 1], t0 + width)
        if hi > lo:
            at = lambda x: p[i] + (p[i + 1] - p[i]) * (x - t[i]) / (t[i + 1] - t[i])
            total += 0.5 * (at(lo) + at(hi)) * (hi - lo)
    return total


def plateau(t, p):
    vals = [v for x, v in zip(t, p) if 3.5 < x < 5.0]
    return sum(vals) / len(vals)


def wets(t, p):
    return next((x for x, v in zip(t, p) if v > 0.05), float("nan"))


r = read_csv(os.path.join(out, "probes.csv"))
t = [x * ts for x in r["time"]]
p1 = [v / ps for v in r["p1"]]
p2 = [v / ps for v in r["p2"]]
exp1 = read_csv(os.path.join(here, "reference", "buchner2002_p1.csv"))
sph1 = read_csv(os.path.join(here, "reference", "marrone2011_p1.csv"))
sph2 = read_csv(os.path.join(here, "reference", "marrone2011_p2.csv"))

ref = {"experiment": (exp1["t_star"], exp1["p_star"]), "delta-SPH H/dx=320": (sph1["t_star"], sph1["p_dSPH_H320"])}
m = {"onset": onset(t, p1), "plateau": plateau(t, p1), "impulse": impulse(t, p1, onset(t, p1), IMPULSE_WINDOW),
     "p2_wets": wets(t, p2), "runup_max": max(v for v in r["runup"] if not math.isnan(v)),
     "above_2H_max": max(r["above_2H"])}
for name, (tr, pr) in ref.items():
    o = onset(tr, pr)
    print("%-20s impact t* %.3f, plateau %.3f, impulse %.3f" % (name, o, plateau(tr, pr), impulse(tr, pr, o, IMPULSE_WINDOW)))
print("%-20s impact t* %.3f, plateau %.3f, impulse %.3f; P2 wet at t* %.2f (experiment %.2f, delta-SPH %.2f); "
      "run-up %.2f m, largest share above 2 H %.2f %%"
      % ("lagfsi " + tag, m["onset"], m["plateau"], m["impulse"], m["p2_wets"], wets(sph2["t_star"], sph2["p_exp"]),
         wets(sph2["t_star"], sph2["p_dSPH_H320"]), m["runup_max"], 100 * m["above_2H_max"]))
exp_onset, sph_onset = onset(*ref["experiment"]), onset(*ref["delta-SPH H/dx=320"])
record("onset", m["onset"])
record("onset_error", m["onset"] / exp_onset - 1)
record("plateau", m["plateau"])
record("plateau_error", m["plateau"] / plateau(*ref["experiment"]) - 1)
record("plateau_error_sph", m["plateau"] / plateau(*ref["delta-SPH H/dx=320"]) - 1)
record("impulse", m["impulse"])
record("impulse_error_sph", m["impulse"] / impulse(*ref["delta-SPH H/dx=320"], sph_onset, IMPULSE_WINDOW) - 1)
record("p2_wets", m["p2_wets"])
record("p2_wets_error", m["p2_wets"] / wets(sph2["t_star"], sph2["p_exp"]) - 1)
record("runup_max", m["runup_max"])
record("above_2H_max", m["above_2H_max"])

fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
ax[0].plot(exp1["t_star"], exp1["p_star"], "k.", ms=3, label="experiment (Buchner 2002)")
ax[0].plot(sph1["t_star"], sph1["p_dSPH_H320"], "b-", lw=1, label="delta-SPH H/dx = 320 (Marrone et al. 2011)")
ax[0].plot(t, p1, "r-", lw=1, label="lagfsi")
ax[0].set_ylabel("P1: p / (rho g H)")
ax[0].set_ylim(-0.2, 1.6)
ax[0].legend(fontsize=8)
ax[1].plot(sph2["t_star"], sph2["p_exp"], "k.", ms=3, label="experiment")
ax[1].plot(sph2["t_star"], sph2["p_dSPH_H320"], "b-", lw=1, label="delta-SPH H/dx = 320")
ax[1].plot(t, p2, "r-", lw=1, label="lagfsi")
ax[1].set_ylabel("P2: p / (rho g H)")
ax[1].set_xlabel("t sqrt(g / H)")
ax[1].set_xlim(2, 6.5)
ax[1].set_ylim(-0.1, 0.5)
save(fig, out, "pressure_%s.png" % tag)
