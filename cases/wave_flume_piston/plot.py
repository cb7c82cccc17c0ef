"""Regular waves from a piston paddle (linear wave-maker theory) against linear wave theory: the wave height and
period at the gauges x = 1.5 and 2.5 m (zero up-crossing analysis of the elevation about the still level, over the
waves that have passed the paddle's ramp and before the end wall's reflection returns), and the phase speed from the
crests' travel between the two gauges. Records: height_1, height_2 (over H), period_1 (over T), celerity (over the
linear celerity), area_drift (the largest |A / A0 - 1|).
Usage: /usr/bin/python3 cases/wave_flume_piston/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/wave_flume_piston")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
ref = {q: v for q, v in zip(*(lambda c: (c["quantity"], c["value"]))(read_csv(os.path.join(here, "reference",
                                                                                              "linear_theory.csv"))))}
H, T, D, C, CG = ref["height_m"], ref["period_s"], 0.4, ref["celerity_m_per_s"], ref["group_velocity_m_per_s"]
FLUME, RAMP = 8.0, 2 * T

p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]


def window(x):
    """From two periods after the ramp's end reached x (at the group velocity) to the reflection's return."""
    return RAMP + x / CG + 2 * T, min(t[-1], (2 * FLUME - x) / CG)


def up_crossings(ts, eta, t0, t1):
    """Times where eta - D crosses zero upwards in [t0, t1] (linear interpolation)."""
    out = []
    for i in range(1, len(ts)):
        a, b = eta[i - 1] - D, eta[i] - D
        if t0 <= ts[i] <= t1 and a < 0 <= b:
            out.append(ts[i - 1] + (ts[i] - ts[i - 1]) * (-a) / (b - a))
    return out


def waves(x, col):
    t0, t1 = window(x)
    ups = up_crossings(t, p[col], t0, t1)
    heights = []
    for a, b in zip(ups, ups[1:]):
        seg = [e for tt, e in zip(t, p[col]) if a <= tt <= b]
        heights.append(max(seg) - min(seg))
    periods = [b - a for a, b in zip(ups, ups[1:])]
    return ups, sum(heights) / len(heights), sum(periods) / len(periods)


ups1, h1, per1 = waves(1.5, "eta_1")
ups2, h2, per2 = waves(2.5, "eta_2")
# The phase speed: each up-crossing at gauge 1 matched with the next at gauge 2 (1 m apart: about half a wavelength).
lags = [min((b - a for b in ups2 if b > a), default=None) for a in ups1]
lags = [l for l in lags if l is not None and l < T]
celerity = 1.0 / (sum(lags) / len(lags))
a0 = p["fluid_area"][0]
area_drift = max(abs(a / a0 - 1) for a in p["fluid_area"])
record("height_1", h1 / H)
record("height_2", h2 / H)
record("period_1", per1 / T)
record("celerity", celerity / C)
record("area_drift", area_drift)
print("%s: wave height %.4f m at x = 1.5 m (%.3f H), %.4f m at 2.5 m (%.3f H); period %.4f s (%.4f T); celerity "
      "%.3f m/s (%.3f of linear); largest area drift %.3f %%"
      % (tag, h1, h1 / H, h2, h2 / H, per1, per1 / T, celerity, celerity / C, 100 * area_drift))

fig, axes = plt.subplots(2, 1, figsize=(11, 5.5), sharex=True)
for ax, col, x in zip(axes, ["eta_1", "eta_2"], [1.5, 2.5]):
    ax.plot(t, [e - D for e in p[col]], lw=0.8, label="lagfsi, x = %.1f m" % x)
    ax.axhline(H / 2, color="k", ls="--", lw=0.8, label="linear theory, +-H/2")
    ax.axhline(-H / 2, color="k", ls="--", lw=0.8)
    t0, t1 = window(x)
    ax.axvspan(t0, t1, color="0.9", label="measured window")
    ax.set_ylabel("elevation [m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
axes[-1].set_xlabel("t [s]")
fig.suptitle("wave_flume_piston (%s)" % tag)
save(fig, out, "comparison_%s.png" % tag)
