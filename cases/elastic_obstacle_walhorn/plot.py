"""Elastic obstacle hit by a dam break (Walhorn et al. 2005): horizontal displacement of the obstacle's top left
corner against the PFEM result of Idelsohn et al. (2008) (reference/idelsohn_2008_pfem_tip_ux.csv) and three
other published solutions (reference/walhorn_numerical_tip_ux.csv). Prints the RMS difference to each over its
points up to the end of the run (and up to 0.45 s, the first swing), both peaks, how far the published solutions
are from one another, and the coupling statistics.
Usage: /usr/bin/python3 cases/elastic_obstacle_walhorn/plot.py OUTDIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, coupling_lines, peak, interp

out = out_dir_from_argv("out/elastic_obstacle_walhorn")
here = os.path.join(os.path.dirname(__file__), "reference")
p = read_csv(os.path.join(out, "probes.csv"))
ref = read_csv(os.path.join(here, "idelsohn_2008_pfem_tip_ux.csv"))
others = read_csv(os.path.join(here, "walhorn_numerical_tip_ux.csv"))
t, ux = p["time"], p["tip_ux"]

SOURCES = [("idelsohn_2008", "Idelsohn et al. 2008 (PFEM)", list(zip(ref["time"], ref["tip_ux"])))]
for src, name in (("bogaers_2016", "Bogaers et al. 2016 (PFEM-FEM, QN-LS)"), ("liu_2013", "Liu et al. 2013 (SPH)"),
                  ("sun_2019", "Sun et al. 2019 (MPS-DEM)")):
    SOURCES.append((src, name, [(a, b) for s, a, b in zip(others["source"], others["time"], others["tip_ux"]) if s == src]))


def rms(pts, tt, uu, t_max):
    pts = [(a, b) for a, b in pts if a <= t_max]
    return math.sqrt(sum((interp(a, tt, uu) - b) ** 2 for a, b in pts) / len(pts)), pts[-1][0]


tp, up = peak(t, ux)
trp, urp = peak(ref["time"], ref["tip_ux"])
e_all, t_end = rms(SOURCES[0][2], t, ux, t[-1])
record("peak", up)
record("peak_time", tp)
lines = ["tip_ux: RMS difference to Idelsohn et al. 2008 %.1f mm over 0-%.2f s; peak %.1f mm at %.3f s "
         "(reference %.1f mm at %.3f s)" % (1e3 * e_all, t_end, 1e3 * up, tp, 1e3 * urp, trp)]
for t_max in (0.45, t[-1]):
    diffs = []
    for src, _, pts in SOURCES:
        e, t_last = rms(pts, t, ux, t_max)
        record("rms_%s_%s" % (src, "045" if t_max == 0.45 else "end"), e)
        diffs.append("%s %.1f (to %.2f s)" % (src, 1e3 * e, t_last))
    lines.append("tip_ux: RMS difference to each published solution [mm]: %s" % ", ".join(diffs))
# The published solutions among themselves: each against the mean of the others on a common grid.
for t_max in (0.45, 0.69):
    grid = [0.01 * k for k in range(int(t_max / 0.01) + 1)]
    curves = {src: [interp(g, [a for a, _ in pts], [b for _, b in pts]) for g in grid] for src, _, pts in SOURCES}
    spread = []
    for src in curves:
        mean = [sum(curves[o][i] for o in curves if o != src) / (len(curves) - 1) for i in range(len(grid))]
        spread.append("%s %.1f" % (src, 1e3 * math.sqrt(sum((c - m) ** 2 for c, m in zip(curves[src], mean)) / len(grid))))
    lines.append("published solutions, each against the mean of the others up to %.2f s [mm]: %s" % (t_max, ", ".join(spread)))
for src, name, pts in SOURCES:
    a, b = peak([x for x, _ in pts], [y for _, y in pts])
    lines.append("  %s: peak %.1f mm at %.3f s" % (name, 1e3 * b, a))
lines += coupling_lines(out)
print("\n".join(lines))

fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
axes[0].plot(t, [1e3 * u for u in ux], label="lagfsi", lw=2)
for (src, name, pts), style in zip(SOURCES, ("k--", ":", "-.", (0, (5, 1, 1, 1)))):
    kw = {"color": "gray"} if src != "idelsohn_2008" else {}
    if isinstance(style, str):
        axes[0].plot([a for a, _ in pts], [1e3 * b for _, b in pts], style, lw=1, label=name, **kw)
    else:
        axes[0].plot([a for a, _ in pts], [1e3 * b for _, b in pts], ls=style, lw=1, label=name, **kw)
axes[0].set_ylabel("tip u_x [mm]")
axes[1].plot(t, [1e3 * u for u in p["tip_uy"]], label="lagfsi")
axes[1].set_ylabel("tip u_y [mm]")
axes[1].set_xlabel("t [s]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_title("elastic obstacle: " + lines[0], fontsize=9)
save(fig, out)
