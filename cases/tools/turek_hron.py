"""The Turek & Hron (2006) cases (cases/turek_hron_*): the benchmark's values, the drag and the lift of the cylinder
with its flag, time means over the last seconds of a run; for the rigid CFD tests their records (claims_record) and
the comparison picture (cfd_forces), and the periodic drag and lift of CFD3 (cfd_oscillation); for the flapping flag
(FSI2, FSI3) its periodic statistics, records and picture (fsi_oscillation)."""
import cmath
import math
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from claims_record import record  # noqa: E402
from lagfsi_post import (last_period_stats, period_amplitudes, read_csv, save, upward_crossings,  # noqa: E402
                         water_balance)


def reference(case_dir, test):
    """The rows of `test` (CFD1, FSI2, ...) in case_dir/reference/turek_hron_2006_<test>.csv: {quantity: [mean,
    amplitude, frequency]} (None where the table has no value)."""
    ref = {}
    with open(os.path.join(case_dir, "reference", "turek_hron_2006_%s.csv" % test.lower())) as f:
        for line in f:
            if line.startswith(test + ","):
                c = line.split(",")
                ref[c[1]] = [float(x) if x.strip() else None for x in c[2:5]]
    return ref


def total_forces(p):
    """The drag and the lift (N/m) of probes `p`: the cylinder's and the flag's added."""
    return ([a + b for a, b in zip(p["drag_cylinder"], p["drag_flag"])],
            [a + b for a, b in zip(p["lift_cylinder"], p["lift_flag"])])


def window_stats(t, window):
    """The start t0 of the last `window` seconds of the times `t`, and the mean and the standard deviation of a
    series over them."""
    t0 = t[-1] - window
    late = [k for k, tk in enumerate(t) if tk >= t0 - 1e-9]

    def mean(v):
        return sum(v[k] for k in late) / len(late)

    def std(v):
        m = mean(v)
        return math.sqrt(sum((v[k] - m) ** 2 for k in late) / len(late))

    return t0, mean, std


def cfd_forces(out, case_dir, test, window, q_in, lift_span):
    """Records drag, lift (N/m: the cylinder's and the flag's forces added), drag_std, lift_std (their standard
    deviations over the window), drag_cylinder, lift_cylinder (the cylinder's share) and discharge (the flow rate at
    x = 1.5 m over the inflow's `q_in`, same window) of the run in `out`, against reference/turek_hron_2006_<test>.csv
    of `case_dir`; draws them (the lift's axis `lift_span` N/m either side of the reference)."""
    tag = os.path.basename(os.path.normpath(out))
    ref = {k: v[0] for k, v in reference(case_dir, test).items()}
    p = read_csv(os.path.join(out, "probes.csv"))
    t = p["time"]
    drag, lift = total_forces(p)
    t0, mean, std = window_stats(t, window)
    values = {"drag": mean(drag), "lift": mean(lift), "drag_std": std(drag), "lift_std": std(lift),
              "drag_cylinder": mean(p["drag_cylinder"]), "lift_cylinder": mean(p["lift_cylinder"]),
              "discharge": mean(p["discharge"]) / q_in, "balance": water_balance(out)}
    for k, v in values.items():
        record(k, v)
    print("%s: drag %.3f N/m (reference %.2f, %+.2f %%, std %.2f), lift %.3f N/m (reference %.3f, %+.1f %%, std "
          "%.2f); cylinder %.3f / %.3f; flow rate %.4f of the inflow's; means over %.1f-%.1f s"
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
        ax.axhline(ref[name], color="k", ls="--", label="Turek & Hron (2006) %s: %.4g" % (test, ref[name]))
        ax.axvspan(t0, t[-1], color="0.9", zorder=0)
        span = 0.5 * ref[name] if name == "drag" else lift_span
        ax.set_ylim(ref[name] - span, ref[name] + span)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("%s [N/m]" % name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("%s (%s): drag %.3f (%+.1f %%), lift %.3f" % (os.path.basename(os.path.normpath(case_dir)), tag,
                 values["drag"], 100 * (values["drag"] / ref["drag"] - 1), values["lift"]))
    save(fig, out, "comparison_%s.png" % tag)


def centred_mean(v, dt, width):
    """A centred running mean of the series v (time step dt) over `width` s."""
    n = max(0, int(round(0.5 * width / dt)))
    return [sum(v[max(0, k - n):k + n + 1]) / len(v[max(0, k - n):k + n + 1]) for k in range(len(v))]


def periodogram_peak_of(tw, w, band):
    """The frequency (Hz, steps of 0.001 Hz within `band`) that maximizes |sum_k (w_k - mean) exp(-2 pi i nu t_k)|
    over the samples w at times tw."""
    m = sum(w) / len(w)
    best = (0.0, 0.0)
    for j in range(int(round(1000 * band[0])), int(round(1000 * band[1])) + 1):
        nu = 0.001 * j
        a = abs(sum((x - m) * cmath.exp(-2j * math.pi * nu * tk) for x, tk in zip(w, tw)))
        best = max(best, (a, nu))
    return best[1]


def phase_average_of(t, v, f, window, bins=40):
    """Mean and amplitude ((max + min)/2, (max - min)/2) of the series v (times t) averaged over the whole periods
    1/f that end the last `window` s, in `bins` phase bins; and the number of periods."""
    n = int(window * f)
    start = t[-1] - n / f
    sums, counts = [0.0] * bins, [0] * bins
    for k, tk in enumerate(t):
        if tk >= start - 1e-9:
            b = min(bins - 1, int(((tk - start) * f % 1.0) * bins))
            sums[b] += v[k]
            counts[b] += 1
    avg = [s_ / c for s_, c in zip(sums, counts) if c > 0]
    return {"mean": 0.5 * (max(avg) + min(avg)), "amplitude": 0.5 * (max(avg) - min(avg)), "periods": n}


def periodic_run(out, case_dir, test):
    """What a periodic case's statistics start from: the run's tag (OUTDIR's last part), the reference rows as
    {quantity: {"mean", "amplitude", "frequency"}}, the probes, their times and step, the drag and the lift."""
    tag = os.path.basename(os.path.normpath(out))
    ref = {k: dict(zip(("mean", "amplitude", "frequency"), v)) for k, v in reference(case_dir, test).items()}
    p = read_csv(os.path.join(out, "probes.csv"))
    t = p["time"]
    drag, lift = total_forces(p)
    return tag, ref, p, t, t[1] - t[0], drag, lift


def cfd_oscillation(out, case_dir, test, window, smooth, band=(1.0, 10.0)):
    """The periodic drag and lift of the rigid obstacle (CFD3) in the run in `out` against
    reference/turek_hron_2006_<test>.csv of `case_dir`, with the flapping flag's conventions (fsi_oscillation): the
    lift's frequency f is the peak of its periodogram over the last `window` s within `band` Hz; the drag's and the
    lift's mean and amplitude are those of their phase average over the whole periods 1/f that end the window, after
    a centred running mean over `smooth` s (the remeshing's step-to-step noise; *_raw_amplitude without it).
    Records drag_mean, drag_amplitude, lift_mean, lift_amplitude, lift_frequency, drag_raw_amplitude,
    lift_raw_amplitude, lift_noise (the standard deviation of the lift about its centred mean, N/m); prints them and
    draws comparison_<OUTDIR's last part>.png."""
    tag, ref, p, t, dt, drag, lift = periodic_run(out, case_dir, test)
    window = min(window, 0.5 * t[-1])
    t0 = t[-1] - window
    late = [k for k, tk in enumerate(t) if tk >= t0 - 1e-9]
    f = periodogram_peak_of([t[k] for k in late], [lift[k] for k in late], band)
    values = {"lift_frequency": f}
    smoothed = {"drag": centred_mean(drag, dt, smooth), "lift": centred_mean(lift, dt, smooth)}
    for name, v in (("drag", drag), ("lift", lift)):
        s = phase_average_of(t, smoothed[name], f, window)
        values[name + "_mean"], values[name + "_amplitude"] = s["mean"], s["amplitude"]
        values[name + "_raw_amplitude"] = phase_average_of(t, v, f, window)["amplitude"]
    values["lift_noise"] = math.sqrt(sum((lift[k] - smoothed["lift"][k]) ** 2 for k in late) / len(late))
    values["balance"] = water_balance(out)
    for k, v in values.items():
        record(k, v)
    periods = int(window * f)
    print("%s: lift frequency %.3f Hz (reference %.4g, %+.1f %%); over %d periods ending at %.2f s:" % (
        tag, f, ref["lift"]["frequency"], 100 * (f / ref["lift"]["frequency"] - 1), periods, t[-1]))
    for name in ("drag", "lift"):
        r = ref[name]
        print("  %-4s mean %8.2f (reference %8.2f)  amplitude %7.2f (reference %7.2f, %+.1f %%; unsmoothed %.2f) N/m"
              % (name, values[name + "_mean"], r["mean"], values[name + "_amplitude"], r["amplitude"],
                 100 * (values[name + "_amplitude"] / r["amplitude"] - 1), values[name + "_raw_amplitude"]))
    print("  the lift's step-to-step noise: %.1f N/m" % values["lift_noise"])

    fig, axes = plt.subplots(2, 1, figsize=(12, 7), sharex=True)
    for ax, name, v in ((axes[0], "drag", drag), (axes[1], "lift", lift)):
        ax.plot(t, v, lw=0.4, color="0.7", label="lagfsi, each step")
        ax.plot(t, smoothed[name], lw=0.8, label="lagfsi, centred mean over %g s" % smooth)
        r = ref[name]
        for y, ls in ((r["mean"], "--"), (r["mean"] + r["amplitude"], ":"), (r["mean"] - r["amplitude"], ":")):
            ax.axhline(y, color="k", ls=ls, lw=0.8)
        ax.plot([], [], color="k", ls=":", label="Turek & Hron (2006) %s: %.4g +- %.4g N/m [%.2f Hz]"
                % (test, r["mean"], r["amplitude"], r["frequency"]))
        ax.axvspan(t0, t[-1], color="0.92", zorder=0)
        ax.set_ylabel("%s [N/m]" % name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    axes[0].set_ylim(0.5 * ref["drag"]["mean"], 1.5 * ref["drag"]["mean"])
    axes[1].set_ylim(-2.5 * ref["lift"]["amplitude"], 2.5 * ref["lift"]["amplitude"])
    axes[1].set_xlabel("t [s]")
    fig.suptitle("%s (%s): lift %.0f +- %.0f N/m [%.2f Hz], drag %.0f +- %.1f N/m" % (
        os.path.basename(os.path.abspath(case_dir)), tag, values["lift_mean"], values["lift_amplitude"], f,
        values["drag_mean"], values["drag_amplitude"]))
    fig.tight_layout()
    save(fig, out, "comparison_%s.png" % tag)
    return values


def fsi_oscillation(out, case_dir, test, window, smooth, band=(0.5, 10.0)):
    """The flag's periodic oscillation in the run in `out` against reference/turek_hron_2006_<test>.csv of `case_dir`,
    as mean = (max + min)/2 and amplitude = (max - min)/2 over a period and the frequency, in the last `window` s of
    the run (the last half of a shorter one).
    The tip's displacements by the benchmark's convention (last_period_stats): the extremes of the last full period,
    the frequency from the spacing of the mid-level's upward crossings in the window. The remeshing's noise makes
    each period's amplitude a sample that varies by a few per cent from one period to the next, so the amplitudes
    are also given per period of u_y(A) over the window (period_amplitudes): their mean (the estimate of the periodic
    state's amplitude that the targets use) and their standard deviation.
    The forces (drag and lift: the cylinder's wall force and the coupling's interface force added) are noisy step by
    step (the remeshing's insertions and removals), so their extremes are those of their phase average: the whole
    periods of u_y(A) that end the window (its frequency f from its crossings) folded onto one, the phase t f mod 1
    in 40 bins, each bin the mean of its samples, after a centred running mean over `smooth` s (drag_raw_amplitude
    and lift_raw_amplitude without it). Their frequency is the peak of the window's periodogram
    |sum_k (F_k - mean) exp(-2 pi i nu t_k)| over nu in `band` Hz (steps of 0.001 Hz). When u_y(A) does not cross
    its mid-level twice in the window (a short run's start-up), every mean and amplitude is (max + min)/2 and
    (max - min)/2 over the window and the tip's frequencies are 0.
    Records: ux_A_mean, ux_A_amplitude, ux_A_frequency, the same for uy_A, drag and lift (m, N/m, Hz),
    ux_A_amplitude_periods and ux_A_amplitude_spread (the per-period amplitudes' mean and standard deviation; the same
    for uy_A), periods_window (their number),
    drag_raw_amplitude, lift_raw_amplitude, iterations (coupling passes per step, mean over the run),
    iterations_window (over the window), iterations_max; prints them and draws comparison_<OUTDIR's last part>.png."""
    tag, ref, p, t, dt, drag, lift = periodic_run(out, case_dir, test)
    name_of_case = os.path.basename(os.path.abspath(case_dir))
    series = {"drag": drag, "lift": lift, "ux_A": p["tip_ux"], "uy_A": p["tip_uy"]}
    steps = [k for k in range(len(t)) if p["fsi_iterations"][k] > 0]

    smoothed = {"drag": centred_mean(series["drag"], dt, smooth), "lift": centred_mean(series["lift"], dt, smooth),
                "ux_A": series["ux_A"], "uy_A": series["uy_A"]}
    window = min(window, 0.5 * t[-1])
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
        return periodogram_peak_of(tw, [v[k] for k in late], band)

    def phase_average_stats(v, f):
        return phase_average_of(t, v, f, window)

    stats = {name: stats_of(series[name]) for name in ("ux_A", "uy_A")}
    f_y = stats["uy_A"]["frequency"]
    raw = {}
    for name in ("drag", "lift"):
        if f_y > 0:
            stats[name] = phase_average_stats(smoothed[name], f_y)
            raw[name] = phase_average_stats(series[name], f_y)
        else:
            stats[name], raw[name] = stats_of(smoothed[name]), stats_of(series[name])
        stats[name]["frequency"] = periodogram_peak(series[name])
    values = {}
    for name, s in stats.items():
        for key in ("mean", "amplitude", "frequency"):
            values["%s_%s" % (name, key)] = s[key]
    for name in ("drag", "lift"):
        values["%s_raw_amplitude" % name] = raw[name]["amplitude"]
    ups = upward_crossings(tw, [series["uy_A"][k] for k in late])
    periods = {name: period_amplitudes(tw, [series[name][k] for k in late], ups) for name in ("ux_A", "uy_A")}
    for name, a in periods.items():
        n = max(1, len(a))
        mean = sum(a) / n
        values["%s_amplitude_periods" % name] = mean
        values["%s_amplitude_spread" % name] = (sum((x - mean) ** 2 for x in a) / n) ** 0.5
    values["periods_window"] = len(periods["uy_A"])
    values["iterations"] = sum(p["fsi_iterations"][k] for k in steps) / max(1, len(steps))
    values["iterations_window"] = sum(p["fsi_iterations"][k] for k in late) / len(late)
    values["iterations_max"] = max(p["fsi_iterations"])
    values["balance"] = water_balance(out)
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
    for name in ("ux_A", "uy_A"):
        print("  %s amplitude per period of uy_A, %d periods: mean %.3f mm (reference %.3f, %+.1f %%), standard "
              "deviation %.3f mm" % (name, values["periods_window"], 1e3 * values["%s_amplitude_periods" % name],
                                     1e3 * ref[name]["amplitude"],
                                     100 * (values["%s_amplitude_periods" % name] / ref[name]["amplitude"] - 1),
                                     1e3 * values["%s_amplitude_spread" % name]))

    fig, axes = plt.subplots(5, 1, figsize=(12, 13), sharex=True)
    for ax, name, scale, unit in ((axes[0], "ux_A", 1e3, "mm"), (axes[1], "uy_A", 1e3, "mm"),
                                  (axes[2], "drag", 1, "N/m"), (axes[3], "lift", 1, "N/m")):
        if name in ("drag", "lift"):
            ax.plot(t, series[name], lw=0.4, color="0.7", label="lagfsi, each step")
            ax.plot(t, [scale * x for x in smoothed[name]], lw=0.8, label="lagfsi, centred mean over %g s" % smooth)
        else:
            ax.plot(t, [scale * x for x in series[name]], lw=0.8, label="lagfsi")
        r = ref[name]
        for y, ls in ((r["mean"], "--"), (r["mean"] + r["amplitude"], ":"), (r["mean"] - r["amplitude"], ":")):
            ax.axhline(scale * y, color="k", ls=ls, lw=0.8)
        ax.plot([], [], color="k", ls=":", label="Turek & Hron (2006) %s: %.4g +- %.4g %s [%.1f Hz]"
                % (test, scale * r["mean"], scale * r["amplitude"], unit, r["frequency"]))
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
    title = ("%s (%s): %.2f coupling passes per step; uy_A %.1f +- %.1f mm [%.2f Hz], drag %.0f +- %.0f N/m"
             % (name_of_case, tag, values["iterations"], 1e3 * stats["uy_A"]["mean"],
                1e3 * stats["uy_A"]["amplitude"], stats["uy_A"]["frequency"], stats["drag"]["mean"],
                stats["drag"]["amplitude"]))
    fig.suptitle(title)
    fig.tight_layout()
    save(fig, out, "comparison_%s.png" % tag)
    return values
