"""The Turek & Hron (2006) cases (cases/turek_hron_*): the benchmark's values, the drag and the lift of the cylinder
with its flag, time means over the last seconds of a run; for the rigid CFD tests their records (claims_record) and
the comparison picture (cfd_forces)."""
import math
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from claims_record import record  # noqa: E402
from lagfsi_post import read_csv, save  # noqa: E402


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
              "discharge": mean(p["discharge"]) / q_in}
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
