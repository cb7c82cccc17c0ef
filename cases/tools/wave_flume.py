"""Regular waves from a wave maker at a flume's left end against linear wave theory: the wave height and period at
gauges (zero up-crossing analysis of the elevation about the still level, over the waves that have passed the
paddle's ramp and before the end wall's reflection returns), and the phase speed from the crests' travel between
two gauges. Used by the wave-flume cases' plot.py (wave_flume_piston, wave_flume_flap); each records height_1,
height_2 (over H), period_1 (over T), celerity (over the linear celerity) and area_drift (the largest |A / A0 - 1|).
The reference CSV (quantity,value) gives height_m, period_s, celerity_m_per_s and group_velocity_m_per_s."""
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save


def analyse(case, out, reference_csv, depth, flume, gauges=(1.5, 2.5), ramp_periods=2):
    tag = os.path.basename(os.path.normpath(out))
    c = read_csv(reference_csv)
    ref = dict(zip(c["quantity"], c["value"]))
    H, T, C, CG = ref["height_m"], ref["period_s"], ref["celerity_m_per_s"], ref["group_velocity_m_per_s"]
    ramp = ramp_periods * T
    p = read_csv(os.path.join(out, "probes.csv"))
    t = p["time"]

    def window(x):
        """From two periods after the ramp's end reached x (at the group velocity) to the reflection's return."""
        return ramp + x / CG + 2 * T, min(t[-1], (2 * flume - x) / CG)

    def up_crossings(eta, t0, t1):
        """Times where eta - depth crosses zero upwards in [t0, t1] (linear interpolation)."""
        ups = []
        for i in range(1, len(t)):
            a, b = eta[i - 1] - depth, eta[i] - depth
            if t0 <= t[i] <= t1 and a < 0 <= b:
                ups.append(t[i - 1] + (t[i] - t[i - 1]) * (-a) / (b - a))
        return ups

    def waves(x, col):
        ups = up_crossings(p[col], *window(x))
        heights = []
        for a, b in zip(ups, ups[1:]):
            seg = [e for tt, e in zip(t, p[col]) if a <= tt <= b]
            heights.append(max(seg) - min(seg))
        periods = [b - a for a, b in zip(ups, ups[1:])]
        return ups, sum(heights) / len(heights), sum(periods) / len(periods)

    ups1, h1, per1 = waves(gauges[0], "eta_1")
    ups2, h2, per2 = waves(gauges[1], "eta_2")
    # The phase speed: each up-crossing at gauge 1 matched with the next at gauge 2 (about half a wavelength on).
    lags = [min((b - a for b in ups2 if b > a), default=None) for a in ups1]
    lags = [lag for lag in lags if lag is not None and lag < T]
    celerity = (gauges[1] - gauges[0]) / (sum(lags) / len(lags))
    a0 = p["fluid_area"][0]
    area_drift = max(abs(a / a0 - 1) for a in p["fluid_area"])
    record("height_1", h1 / H)
    record("height_2", h2 / H)
    record("period_1", per1 / T)
    record("celerity", celerity / C)
    record("area_drift", area_drift)
    print("%s: wave height %.4f m at x = %.1f m (%.3f H), %.4f m at %.1f m (%.3f H); period %.4f s (%.4f T); "
          "celerity %.3f m/s (%.3f of linear); largest area drift %.3f %%"
          % (tag, h1, gauges[0], h1 / H, h2, gauges[1], h2 / H, per1, per1 / T, celerity, celerity / C,
             100 * area_drift))

    fig, axes = plt.subplots(2, 1, figsize=(11, 5.5), sharex=True)
    for ax, col, x in zip(axes, ["eta_1", "eta_2"], gauges):
        ax.plot(t, [e - depth for e in p[col]], lw=0.8, label="lagfsi, x = %.1f m" % x)
        ax.axhline(H / 2, color="k", ls="--", lw=0.8, label="linear theory, +-H/2")
        ax.axhline(-H / 2, color="k", ls="--", lw=0.8)
        t0, t1 = window(x)
        ax.axvspan(t0, t1, color="0.9", label="measured window")
        ax.set_ylabel("elevation [m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("%s (%s)" % (case, tag))
    save(fig, out, "comparison_%s.png" % tag)
