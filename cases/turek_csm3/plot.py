"""Tip displacement history of the Turek-Hron flag released under gravity (CSM3) against the benchmark
mean +- amplitude [frequency]. Usage: /usr/bin/python3 cases/turek_csm3/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, last_period_stats

out = out_dir_from_argv("out/turek_csm3")
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "turek_hron_2006_reference_values.csv"))
rv = {q: (m, a, f) for c, q, m, a, f in zip(ref["case"], ref["quantity"], ref["mean"], ref["amplitude"],
                                             ref["frequency_Hz"]) if c == "CSM3"}
p = read_csv(os.path.join(out, "probes.csv"))
fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
for ax, key, q in zip(axes, ("tip_ux", "tip_uy"), ("ux_A", "uy_A")):
    m, a, f = rv[q]
    s = last_period_stats(p["time"], p[key])
    ax.plot(p["time"], p[key], label="lagfsi")
    ax.axhline(m, color="k", ls="--", lw=0.8, label="Turek & Hron mean")
    ax.axhspan(m - a, m + a, color="gray", alpha=0.15, label="Turek & Hron mean +- amplitude")
    if s:
        for k in ("mean", "amplitude", "frequency"):
            record("%s_%s" % (q, k), s[k])
        print("%s: mean %.4e (ref %.4e, %+.2f %%), amplitude %.4e (ref %.4e, %+.2f %%), frequency %.4f Hz (ref %.4f, %+.2f %%)"
              % (q, s["mean"], m, 100 * (s["mean"] / m - 1), s["amplitude"], a, 100 * (s["amplitude"] / a - 1),
                 s["frequency"], f, 100 * (s["frequency"] / f - 1)))
    ax.set_ylabel(key + " [m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
axes[-1].set_xlabel("time [s]")
axes[0].set_title("Turek-Hron CSM3 (dynamic, gravity)")
save(fig, out)
