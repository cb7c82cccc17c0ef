"""Sloshing in a wedge (a 90-degree V-shaped tank): the elevations at x = -0.15 and 0.15 m against the exact linear
mode (eta = eps x cos(omega t), omega^2 = g / d; Lamb 1932, art. 258), its period, the amplitude after 10 periods,
the wave's energy and the water's drift.
Usage: /usr/bin/python3 cases/sloshing_wedge/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, last_period_stats

out = out_dir_from_argv("out/sloshing_wedge")
rho, g, eps = 1000.0, 9.81, 0.025
p = read_csv(os.path.join(out, "probes.csv"))
t, A = p["time"], p["fluid_area"]
# The still water of the same area: a triangle of depth d, A = d^2 (the initial one is 0.04 / (1 - eps^2)).
d = math.sqrt(A[0])
T = 2 * math.pi * math.sqrt(d / g)
# Energies: potential of the still triangle of the area at that time, -rho g int y dA = rho g (2/3) A^(3/2); the
# wave's energy is the rest (against the initial area instead, an area change of 1e-5 would read as 5 % of it).
def wave(i):
    return (p["kinetic_energy"][i] + p["potential_energy"][i] - rho * g * 2.0 / 3.0 * A[i] ** 1.5 +
            p["viscous_dissipation"][i])
e0 = wave(0)
periods = int(t[-1] / T + 1e-6)
end = min(range(len(t)), key=lambda i: abs(t[i] - periods * T))
record("wave_energy_start", e0)
record("wave_energy_ratio", wave(end) / e0)
record("ke_max", max(p["kinetic_energy"]))
water = p["water_area"] if "water_area" in p else A
record("water_drift_max", max(abs(a / water[0] - 1) for a in water))
record("area_drift_max", max(abs(a / A[0] - 1) for a in A))
stats, rms = {}, {}
for name, x in (("eta_left", -0.15), ("eta_right", 0.15)):
    s = last_period_stats(t, p[name])
    a_mode = eps * abs(x)  # the mode's amplitude there
    # RMS error against the exact mode over the whole run (about the still level d), over the mode's amplitude
    err = [(e - d) - eps * x * math.cos(2 * math.pi * tt / T) for tt, e in zip(t, p[name])]
    rms[name] = math.sqrt(sum(e * e for e in err) / len(err)) / a_mode
    record(name + "_rms", rms[name])
    stats[name] = s
    record(name + "_period", 1 / s["frequency"])
    record(name + "_amplitude_ratio", s["amplitude"] / a_mode)
    print("%s: RMS error %.4f of the mode's amplitude over %.2f s; period %.5f s (exact linear mode %.5f s, %+.2f %%);"
          " amplitude over the last period %.3f mm (the mode's %.3f mm, %+.1f %%), after %d periods"
          % (name, rms[name], t[-1], 1 / s["frequency"], T, 100 * (1 / s["frequency"] / T - 1), 1e3 * s["amplitude"],
             1e3 * a_mode, 100 * (s["amplitude"] / a_mode - 1), s["periods"]))
period = 0.5 * (1 / stats["eta_left"]["frequency"] + 1 / stats["eta_right"]["frequency"])
record("period", period)
record("period_exact", T)
print("wave energy %.5f J/m at the start (linear mode rho g eps^2 d^3 / 3 = %.5f), %.4f of it after %d periods;"
      " largest kinetic energy %.5f J/m; water drift %.1e, mesh %.1e"
      % (e0, rho * g * eps ** 2 * d ** 3 / 3, wave(end) / e0, periods, max(p["kinetic_energy"]),
         max(abs(a / water[0] - 1) for a in water), max(abs(a / A[0] - 1) for a in A)))
fig, ax = plt.subplots(figsize=(8, 3.5))
ts = [i * 0.005 for i in range(int(t[-1] / 0.005) + 1)]
for name, x, c in (("eta_left", -0.15, "C0"), ("eta_right", 0.15, "C1")):
    ax.plot(t, [1e3 * (e - d) for e in p[name]], c, label="lagfsi, x = %.2f m" % x)
    ax.plot(ts, [1e3 * eps * x * math.cos(2 * math.pi * tt / T) for tt in ts], "k--", lw=0.6)
ax.plot([], [], "k--", lw=0.6, label="exact linear mode")
ax.set_xlabel("t [s]")
ax.set_ylabel("elevation [mm]")
ax.set_title("sloshing in a wedge: RMS error %.3f / %.3f of the mode, wave energy kept %.4f"
             % (rms["eta_left"], rms["eta_right"], wave(end) / e0))
ax.legend(fontsize=8, loc="upper right")
ax.grid(alpha=0.3)
save(fig, out)
