"""Free first-mode sloshing: wall elevation history, its period against the linear theory and the decay.
Usage: /usr/bin/python3 cases/sloshing_free/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, last_period_stats

out = out_dir_from_argv("out/sloshing_free")
L, d, g = 1.0, 0.5, 9.81
T1 = 2 * math.pi / math.sqrt(g * math.pi / L * math.tanh(math.pi / L * d))
p = read_csv(os.path.join(out, "probes.csv"))
s = last_period_stats(p["time"], p["eta_left"])
a0 = p["eta_left"][0] - d
record("period", 1 / s["frequency"])
record("amplitude_ratio", s["amplitude"] / a0)
record("periods", s["periods"])
print("period %.5f s (linear theory %.5f s, %+.2f %%); amplitude after %d periods %.5f m (initial %.5f m, %+.2f %%)"
      % (1 / s["frequency"], T1, 100 * (1 / s["frequency"] / T1 - 1), s["periods"], s["amplitude"], a0,
         100 * (s["amplitude"] / a0 - 1)))
fig, ax = plt.subplots(figsize=(8, 3.5))
ax.plot(p["time"], [1e3 * (e - d) for e in p["eta_left"]], label="lagfsi, left wall")
ts = [i * 0.01 for i in range(int(p["time"][-1] / 0.01) + 1)]
ax.plot(ts, [1e3 * a0 * math.cos(2 * math.pi * t / T1) for t in ts], "k--", lw=0.8, label="linear theory")
ax.set_xlabel("t [s]")
ax.set_ylabel("elevation [mm]")
ax.set_title("free sloshing: period %+.2f %% from linear theory" % (100 * (1 / s["frequency"] / T1 - 1)))
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
save(fig, out)
