"""Plane Poiseuille flow through an open channel (inflow, outflow, no-slip walls) against the exact solution: the
velocity profile at mid-channel (x = 0.25 m), the pressure drop between x = 0.1 and 0.4 m and the flow rate through
x = 0.25 m, over the last two seconds of the run (after the start-up); the velocities and the flow rate at the end.
Records: drop_mean (Pa, exact 18) and drop_std, discharge (over the exact U H), center (the centre-line velocity over
1.5 U), profile_rms (RMS of the profile's error over 1.5 U at the nine points y = 0.01 ... 0.09 m), area_drift (the
largest |A / A0 - 1|), balance (the water balance: ((A(T) - A(0)) - (inflow - outflow)) over the inflow, summary.json).
Usage: /usr/bin/python3 cases/channel_poiseuille/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, water_balance

out = out_dir_from_argv("out/channel_poiseuille")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
H, U, MU, T0 = 0.1, 0.05, 1.0, 1.0
DROP = 12 * MU * U / H**2 * 0.3  # Pa between x = 0.1 and 0.4 m

p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(here, "reference", "poiseuille_exact.csv"))
t = p["time"]
late = [k for k, tk in enumerate(t) if tk >= T0 - 1e-9]
drop = [p["p_in"][k] - p["p_out"][k] for k in range(len(t))]
drop_mean = sum(drop[k] for k in late) / len(late)
drop_std = math.sqrt(sum((drop[k] - drop_mean) ** 2 for k in late) / len(late))
discharge = sum(p["discharge"][k] for k in late) / len(late) / (U * H)
ys = [k / 100 for k in range(1, 10)]
exact = [6 * U * y * (H - y) / H**2 for y in ys]
u_end = [p["u_%02d" % k][-1] for k in range(1, 10)]
center = u_end[4] / (1.5 * U)
rms = math.sqrt(sum((a - b) ** 2 for a, b in zip(u_end, exact)) / len(ys)) / (1.5 * U)
a0 = p["fluid_area"][0]
area_drift = max(abs(a / a0 - 1) for a in p["fluid_area"])
record("drop_mean", drop_mean)
record("drop_std", drop_std)
record("discharge", discharge)
record("center", center)
record("profile_rms", rms)
record("area_drift", area_drift)
record("balance", water_balance(out))
print("%s: pressure drop %.2f Pa (exact %.2f, %+.1f %%), std %.2f Pa; flow rate %.4f of U H; centre-line %.4f of 1.5 U; "
      "profile RMS %.4f of 1.5 U; largest area drift %.2f %%"
      % (tag, drop_mean, DROP, 100 * (drop_mean / DROP - 1), drop_std, discharge, center, rms, 100 * area_drift))

fig, axes = plt.subplots(1, 3, figsize=(14, 3.8))
axes[0].plot(ref["u_m_per_s"], ref["y_m"], "k-", label="exact")
axes[0].plot(u_end, ys, "o", label="lagfsi, x = 0.25 m, t = %.1f s" % t[-1])
axes[0].set_xlabel("u [m/s]")
axes[0].set_ylabel("y [m]")
axes[1].plot(t, drop, lw=0.8, label="lagfsi, p(0.1) - p(0.4)")
axes[1].axhline(DROP, color="k", ls="--", label="exact 12 mu U L / H^2")
axes[1].axvline(T0, color="0.6", lw=0.8)
axes[1].set_ylim(0, 2.5 * DROP)
axes[1].set_xlabel("t [s]")
axes[1].set_ylabel("pressure drop [Pa]")
axes[2].plot(t, [q / (U * H) for q in p["discharge"]], lw=0.8, label="lagfsi, x = 0.25 m")
axes[2].axhline(1.0, color="k", ls="--", label="inflow U H")
axes[2].set_ylim(0.9, 1.05)
axes[2].set_xlabel("t [s]")
axes[2].set_ylabel("flow rate / (U H)")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("channel_poiseuille (%s)" % tag)
save(fig, out, "comparison_%s.png" % tag)
