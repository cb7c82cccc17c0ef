"""Turek & Hron (2006) FSI2: the flag's oscillation behind the cylinder at Re = 100 against the benchmark's values
(reference/turek_hron_2006_fsi2.csv), as mean = (max + min)/2 and amplitude = (max - min)/2 over a period and the
frequency, in the last 4 s of the run (the last half of a shorter one).
The tip's displacements by the benchmark's convention (cases/tools/lagfsi_post, last_period_stats): the extremes of
the last full period, the frequency from the spacing of the mid-level's upward crossings in the window.
The forces (drag and lift: the cylinder's wall force and the coupling's interface force added) are noisy step by
step (the remeshing's insertions and removals), so their extremes are those of their phase average: the whole
periods of u_y(A) that end the window (its frequency f from its crossings) folded onto one, the phase t f mod 1 in
40 bins, each bin the mean of its samples, after a centred running mean over 0.025 s (ten steps of 2.5 ms, a tenth of
the drag's period; drag_raw_amplitude and lift_raw_amplitude without it). Their frequency is the peak of the
window's periodogram |sum_k (F_k - mean) exp(-2 pi i nu t_k)| over nu in 0.5-10 Hz (steps of 0.001 Hz). When u_y(A)
does not cross its mid-level twice in the window (a short run's start-up), every mean and amplitude is
(max + min)/2 and (max - min)/2 over the window and the tip's frequencies are 0.
Records: ux_A_mean, ux_A_amplitude, ux_A_frequency, the same for uy_A, drag and lift (m, N/m, Hz),
drag_raw_amplitude, lift_raw_amplitude, iterations (coupling passes per step, mean over the run), iterations_window
(over the window), iterations_max.
Usage: /usr/bin/python3 cases/turek_hron_fsi2/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import cmath
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, last_period_stats
from turek_hron import reference, total_forces

out = out_dir_from_argv("out/turek_hron_fsi2")
tag = os.path.basename(os.path.normpath(out))
here = os.path.dirname(__file__)
WINDOW = 4.0  # s, the window of the statistics at the end of the run (about eight periods of u_y)
SMOOTH = 0.025  # s, the forces' centred running mean

ref = {k: dict(zip(("mean", "amplitude", "frequency"), v)) for k, v in reference(here, "FSI2").items()}

p = read_csv(os.path.join(out, "probes.csv"))
t = p["time"]
dt = t[1] - t[0]
drag, lift = total_forces(p)
series = {"drag": drag, "lift": lift, "ux_A": p["tip_ux"], "uy_A": p["tip_uy"]}
steps = [k for k in range(len(t)) if p["fsi_iterations"][k] > 0]


def centred_mean(v, width):
    n = max(0, int(round(0.5 * width / dt)))
    return [sum(v[max(0, k - n):k + n + 1]) / len(v[max(0, k - n):k + n + 1]) for k in range(len(v))]


smooth = {"drag": centred_mean(series["drag"], SMOOTH), "lift": centred_mean(series["lift"], SMOOTH),
          "ux_A": series["ux_A"], "uy_A": series["uy_A"]}
window = min(WINDOW, 0.5 * t[-1])
t0 = t[-1] - window
late = [k for k, tk in enumerate(t) if tk >= t0 - 1e-9]
tw = [t[k] for k in late]


def stats_of(v):
    w = [v[k] for k in late]
    s = last_period_stats(tw, w)
    if s is None:
        s = {"mean": 0.5 * (max(w) + min(w)), "amplitude": 0.5 * (max(w) - min(w)), "frequency": 0.0, "periods": 0}
    return s


def periodogram_peak(v):
    w = [v[k] for k in late]
    m = sum(w) / len(w)
    best = (0.0, 0.0)
    for j in range(500, 10001):
        nu = 0.001 * j
        a = abs(sum((x - m) * cmath.exp(-2j * math.pi * nu * tk) for x, tk in zip(w, tw)))
        best = max(best, (a, nu))
    return best[1]


def phase_average_stats(v, f, bins=40):
    """Mean and amplitude of v's average over the whole periods 1/f that end the window, in phase bins."""
    n = int(window * f)
    start = t[-1] - n / f
    sums, counts = [0.0] * bins, [0] * bins
    for k in late:
        if t[k] >= start - 1e-9:
            b = min(bins - 1, int(((t[k] - start) * f % 1.0) * bins))
            sums[b] += v[k]
            counts[b] += 1
    avg = [s_ / c for s_, c in zip(sums, counts) if c > 0]
    return {"mean": 0.5 * (max(avg) + min(avg)), "amplitude": 0.5 * (max(avg) - min(avg)), "periods": n}


stats = {name: stats_of(series[name]) for name in ("ux_A", "uy_A")}
f_y = stats["uy_A"]["frequency"]
raw = {}
for name in ("drag", "lift"):
    if f_y > 0:
        stats[name] = phase_average_stats(smooth[name], f_y)
        raw[name] = phase_average_stats(series[name], f_y)
    else:
        stats[name], raw[name] = stats_of(smooth[name]), stats_of(series[name])
    stats[name]["frequency"] = periodogram_peak(series[name])
values = {}
for name, s in stats.items():
    for key in ("mean", "amplitude", "frequency"):
        values["%s_%s" % (name, key)] = s[key]
for name in ("drag", "lift"):
    values["%s_raw_amplitude" % name] = raw[name]["amplitude"]
values["iterations"] = sum(p["fsi_iterations"][k] for k in steps) / max(1, len(steps))
values["iterations_window"] = sum(p["fsi_iterations"][k] for k in late) / len(late)
values["iterations_max"] = max(p["fsi_iterations"])
for k, v in values.items():
    record(k, v)


def err(name, key):
    return 100 * (stats[name][key] / ref[name][key] - 1)


print("%s: %.2f coupling passes per step (at most %d; %.2f over the window)"
      % (tag, values["iterations"], values["iterations_max"], values["iterations_window"]))
for name, scale, unit in (("ux_A", 1e3, "mm"), ("uy_A", 1e3, "mm"), ("drag", 1, "N/m"), ("lift", 1, "N/m")):
    s, r = stats[name], ref[name]
    print("  %-5s mean %9.3f (reference %9.3f, %+.1f %%)  amplitude %8.3f (reference %8.3f, %+.1f %%)  "
          "frequency %.3f Hz (reference %.1f, %+.1f %%)  %s, %d periods over %.2f-%.2f s"
          % (name, scale * s["mean"], scale * r["mean"], err(name, "mean"), scale * s["amplitude"],
             scale * r["amplitude"], err(name, "amplitude"), s["frequency"], r["frequency"],
             err(name, "frequency"), unit, s["periods"], t0, t[-1]))
print("  raw (unsmoothed) amplitudes: drag %.2f N/m, lift %.2f N/m" % (values["drag_raw_amplitude"],
                                                                      values["lift_raw_amplitude"]))

fig, axes = plt.subplots(5, 1, figsize=(12, 13), sharex=True)
for ax, name, scale, unit in ((axes[0], "ux_A", 1e3, "mm"), (axes[1], "uy_A", 1e3, "mm"),
                              (axes[2], "drag", 1, "N/m"), (axes[3], "lift", 1, "N/m")):
    if name in ("drag", "lift"):
        ax.plot(t, series[name], lw=0.4, color="0.7", label="lagfsi, each step")
        ax.plot(t, [scale * x for x in smooth[name]], lw=0.8, label="lagfsi, centred mean over %g s" % SMOOTH)
    else:
        ax.plot(t, [scale * x for x in series[name]], lw=0.8, label="lagfsi")
    r = ref[name]
    for y, ls in ((r["mean"], "--"), (r["mean"] + r["amplitude"], ":"), (r["mean"] - r["amplitude"], ":")):
        ax.axhline(scale * y, color="k", ls=ls, lw=0.8)
    ax.plot([], [], color="k", ls=":", label="Turek & Hron (2006) FSI2: %.4g +- %.4g %s [%.1f Hz]"
            % (scale * r["mean"], scale * r["amplitude"], unit, r["frequency"]))
    ax.axvspan(t0, t[-1], color="0.92", zorder=0)
    ax.set_ylabel("%s [%s]" % (name, unit))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
axes[2].set_ylim(0, 2.5 * ref["drag"]["mean"] + 2 * ref["drag"]["amplitude"])
axes[3].set_ylim(-2 * ref["lift"]["amplitude"], 2 * ref["lift"]["amplitude"])
axes[4].plot(t, p["fsi_iterations"], lw=0.5)
axes[4].set_ylabel("coupling passes")
axes[4].set_xlabel("t [s]")
axes[4].grid(alpha=0.3)
title = ("turek_hron_fsi2 (%s): %.2f coupling passes per step; uy_A %.1f +- %.1f mm [%.2f Hz], drag %.0f +- %.0f N/m"
         % (tag, values["iterations"], 1e3 * stats["uy_A"]["mean"], 1e3 * stats["uy_A"]["amplitude"],
            stats["uy_A"]["frequency"], stats["drag"]["mean"], stats["drag"]["amplitude"]))
fig.suptitle(title)
fig.tight_layout()
save(fig, out, "comparison_%s.png" % tag)
