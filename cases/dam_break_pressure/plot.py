"""Dam break against a wall with pressure sensors (Zhou, De Kat & Buchner 1999; Buchner 2002; Marrone et al. 2011):
the pressure at P1 (y = 0.16 m) and P2 (y = 0.584 m) on the impacted wall in p* = p / (rho g H) against
t* = t sqrt(g / H), with the experiment and the converged delta-SPH reference, and the measures of the issue:
the impact time at P1 (the last time p* < 0.05 before it first exceeds 0.3), the quasi-static plateau (the mean of
p* over 3.5 < t* < 5), the pressure impulse of the first 0.1 s after the impact, the time the run-up wets P2
(p* > 0.05), the run-up's highest point and the largest share of the water above 2 H; with a p1_load column
(the load sensor over P1's face), P1's impact, plateau and impulse read from the wall's load too.
Usage: /usr/bin/python3 cases/dam_break_pressure/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save
import wall_pressure as wp

out = out_dir_from_argv("out/dam_break_pressure")
tag = os.path.basename(os.path.normpath(out))
m = wp.measures(read_csv(os.path.join(out, "probes.csv")))
exp1, sph1, sph2 = wp.references()
ref = wp.reference_measures()
print("%-20s impact t* %.3f, plateau %.3f, impulse %.3f" % ("experiment", ref["exp_onset"], ref["exp_plateau"],
                                                             ref["exp_impulse"]))
print("%-20s impact t* %.3f, plateau %.3f, impulse %.3f" % ("delta-SPH H/dx=320", ref["sph_onset"], ref["sph_plateau"],
                                                             ref["sph_impulse"]))
print("%-20s impact t* %.3f, plateau %.3f, impulse %.3f; P2 wet at t* %.2f (experiment %.2f, delta-SPH %.2f); "
      "run-up %.2f m, largest share above 2 H %.2f %%"
      % ("lagfsi " + tag, m["onset"], m["plateau"], m["impulse"], m["p2_wets"], ref["exp_p2_wets"],
         ref["sph_p2_wets"], m["runup_max"], 100 * m["above_2H_max"]))
record("onset", m["onset"])
record("onset_error", m["onset"] / ref["exp_onset"] - 1)
record("plateau", m["plateau"])
record("plateau_error", m["plateau"] / ref["exp_plateau"] - 1)
record("plateau_error_sph", m["plateau"] / ref["sph_plateau"] - 1)
record("impulse", m["impulse"])
record("impulse_error_sph", m["impulse"] / ref["sph_impulse"] - 1)
record("p2_wets", m["p2_wets"])
record("p2_wets_error", m["p2_wets"] / ref["exp_p2_wets"] - 1)
record("runup_max", m["runup_max"])
record("above_2H_max", m["above_2H_max"])
if "p1_load" in m:
    print("%-20s P1 from the wall's load: impact t* %.3f, plateau %.3f, impulse %.3f"
          % ("lagfsi " + tag, m["onset_load"], m["plateau_load"], m["impulse_load"]))
    record("onset_load", m["onset_load"])
    record("plateau_load", m["plateau_load"])
    record("impulse_load", m["impulse_load"])
t, p1, p2 = m["t"], m["p1"], m["p2"]

fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
ax[0].plot(exp1["t_star"], exp1["p_star"], "k.", ms=3, label="experiment (Buchner 2002)")
ax[0].plot(sph1["t_star"], sph1["p_dSPH_H320"], "b-", lw=1, label="delta-SPH H/dx = 320 (Marrone et al. 2011)")
ax[0].plot(t, p1, "r-", lw=1, label="lagfsi")
if "p1_load" in m:
    ax[0].plot(t, m["p1_load"], "m-", lw=0.6, alpha=0.7, label="lagfsi, the wall's load over P1")
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
