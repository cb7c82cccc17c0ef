"""Study: the air-blast crater runs of Sabatucci et al. (CILAMCE 2013) beyond the paper's model A2.

cases/dem_blast_crater (1 kg TNT 0.5 m above a 1.2 m x 0.427 m bed, the paper's contact law, 40 ms) with
  A1: kn = 2.75e5 N/m, A2: 2.75e4 (the case), A3: 1.1e4 (4 mm discs);
  B1: 3 mm discs, B2: 6 mm discs (kn = 2.75e4);
  C: a 0.15 m layer of 4 mm discs over 6 mm discs (kn = 2.75e4).
Per run: crater depth (mean at the centre and +-0.05 m) and diameter at the end (crater.csv), the times of the
kinetic-energy peaks at the depths 0.05, 0.10, 0.20 and 0.30 m and the delay 0.05 -> 0.10 m, against the paper's
Tables 3-4 and its delays (A1 0.72 ms, A2 1.4412 ms, A3 2.2042 ms); disc count, marked discs, CPU time and
particle-steps per second.

The full mode also runs a time-step sweep: model A2's law on a 0.4 m x 0.2 m bed for 5 ms with dt = 1e-6, 5e-7,
2e-7 and 1e-7 s (shadowing every step): crater depth at 5 ms against dt.

Options besides the common ones: --dt (sub-step, default 1e-7 s, the paper's), --exposure-every (blast shadowing
recomputed every N sub-steps, default 1, the paper's), --end-time (default 0.04 s), --models A1,A2,... (default
all), --gravity (g = 9.81 m/s^2; default off, as the case), --no-sweep (skip the time-step sweep; its published
table and chart stay as they are). With --publish the README's Measured table is generated from the runs. --quick: a 0.3 m x 0.1 m bed for 2 ms, models A2 and
C, and the sweep at dt = 1e-6 and 5e-7 s (a smoke test of the script, not of the numbers).
Usage: /usr/bin/python3 run.py [--quick] [--dt 1e-7] [--exposure-every 1] [--models A1,A2] [--threads 2] ..."""
import argparse
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

ap = argparse.ArgumentParser(add_help=False)
ap.add_argument("--dt", type=float, default=1e-7)
ap.add_argument("--exposure-every", type=int, default=1)
ap.add_argument("--end-time", type=float, default=0.04)
ap.add_argument("--models", default="A1,A2,A3,B1,B2,C")
ap.add_argument("--gravity", action="store_true")
ap.add_argument("--no-sweep", action="store_true")
extra, rest = ap.parse_known_args()
S = common.Study("dem_blast", __doc__.splitlines()[0], rest)

# model: kn [N/m], layers [(radius, thickness from the bottom or None = to the top)], paper depth [m], paper delay [ms]
MODELS = {"A1": (2.75e5, [(0.002, None)], 0.027, 0.72), "A2": (2.75e4, [(0.002, None)], 0.053, 1.4412),
          "A3": (1.1e4, [(0.002, None)], 0.066, 2.2042), "B1": (2.75e4, [(0.0015, None)], 0.054, None),
          "B2": (2.75e4, [(0.003, None)], 0.053, None), "C": (2.75e4, [(0.003, 0.277), (0.002, None)], 0.055, None)}
FIELD = (0.045, 0.050)  # Ambrosini et al. (2002) B1b, B1a
DEPTHS = [("ke_005", 0.05), ("ke_010", 0.10), ("ke_020", 0.20), ("ke_030", 0.30)]
if S.quick:
    WIDTH, HEIGHT, END, DT, EVERY, NAMES = 0.3, 0.1, 0.002, 1e-6, 10, ["A2", "C"]
    SWEEP = (0.3, 0.1, 0.002, [1e-6, 5e-7])
    MODELS["C"] = (2.75e4, [(0.003, 0.05), (0.002, None)], 0.055, None)
    DEPTHS = [("ke_005", 0.02), ("ke_010", 0.04), ("ke_020", 0.06), ("ke_030", 0.08)]
else:
    WIDTH, HEIGHT, END, DT, EVERY, NAMES = 1.2, 0.427, extra.end_time, extra.dt, extra.exposure_every, \
        extra.models.split(",")
    SWEEP = (0.4, 0.2, 0.005, [1e-6, 5e-7, 2e-7, 1e-7])


def sets(name, WIDTH=WIDTH, HEIGHT=HEIGHT, END=END, DT=DT, EVERY=EVERY):
    kn, layers, _, _ = MODELS[name]
    discs, bottom = [], 0.0
    for r, thick in layers:
        h = (HEIGHT - bottom) if thick is None else thick
        discs.append({"type": "hex_lattice", "region": {"type": "rectangle", "origin": [0.0, bottom], "size": [WIDTH, h]},
                      "radius": r})
        bottom += h
    surface = HEIGHT - 0.0004  # the hexagonal beds end within 0.4 mm of the region's top
    s = {"bodies.0.contact.kn": kn, "bodies.0.discs": discs, "bodies.0.time_step.dt": DT,
         "bodies.0.blast.exposure_every": EVERY, "bodies.0.blast.position": [WIDTH / 2, surface + 0.5],
         "analysis.end_time": END, "output.every": 500 if not S.quick else 100,
         "probes": [{"name": c, "type": "ke_near", "body": "bed", "at": [WIDTH / 2, surface - d], "count": 6}
                    for c, d in DEPTHS] + [{"name": "kinetic", "type": "energy", "body": "bed", "kind": "kinetic"},
                                           {"name": "blast_work", "type": "energy", "body": "bed", "kind": "blast_work"}]}
    if WIDTH != 1.2:
        s["bodies.0.walls"] = [{"name": "box", "points": [[0.0, HEIGHT + 0.1], [0.0, 0.0], [WIDTH, 0.0], [WIDTH, HEIGHT + 0.1]]}]
    if extra.gravity:
        s["gravity"] = [0.0, -9.81]
    return s


rows, series = [], {}
for name in NAMES:
    kn, layers, depth_ref, delay_ref = MODELS[name]
    tag = "%s_dt%g_e%d%s" % (name, DT, EVERY, "_g" if extra.gravity else "")
    r = S.run("dem_blast_crater/case.json", tag, sets(name), timeout=None if not S.quick else 300)
    row = {"model": name, "kn": kn, "d_mm": "/".join("%g" % (2000 * q) for q, _ in layers), "dt": DT,
           "exposure_every": EVERY, "gravity": int(extra.gravity), "exit_code": r.rc, "paper_depth": depth_ref,
           "paper_delay_ms": delay_ref if delay_ref else float("nan")}
    if r.rc == 0:
        b = r.summary["bodies"][0]
        row.update({"discs": b["discs"], "marked": b["marked_discs"], "wall_time_s": b["wall_time"],
                    "particle_steps_per_s": b["particle_steps_per_second"]})
        text = open(os.path.join(r.out, "crater.csv")).read()
        m = re.search(r"depth = ([-0-9.eE+]+) m .*diameter = ([-0-9.eE+]+) m", text)
        row["depth"], row["diameter"] = float(m.group(1)), float(m.group(2))
        p = r.probes()
        t = p["time"]
        for c, d in DEPTHS:
            ke = p[c]
            k = max(range(len(ke)), key=lambda i: ke[i])
            row["peak_%s_ms" % c[3:]] = 1e3 * t[k]
            row["peak_ke_%s" % c[3:]] = ke[k]
        row["delay_ms"] = row["peak_010_ms"] - row["peak_005_ms"]
        series[name] = (t, [p[c] for c, _ in DEPTHS])
    rows.append(row)

cols = ["model", "kn", "d_mm", "dt", "exposure_every", "gravity", "exit_code", "discs", "marked", "depth", "paper_depth",
        "diameter", "peak_005_ms", "peak_010_ms", "peak_020_ms", "peak_030_ms", "delay_ms", "paper_delay_ms",
        "peak_ke_005", "peak_ke_010", "peak_ke_020", "peak_ke_030", "wall_time_s", "particle_steps_per_s"]
S.table("dem_blast_runs.csv", rows, cols)


def num(v, f):
    return f % v if isinstance(v, float) and math.isfinite(v) else "–"


loads = []
for name in NAMES:
    try:
        with open(os.path.join(S.runs_dir, "%s_dt%g_e%d%s" % (name, DT, EVERY, "_g" if extra.gravity else ""),
                               "study_run.json")) as f:
            loads.append(json.load(f)["load_before"])
    except (OSError, ValueError, KeyError):
        pass
md = ["**Measured** (generated by `run.py --publish`: commit %s, Δt = %s s, shadowing every %s, %d thread%s%s; "
      "the 1-minute load average before the runs %s on %d cores):" %
      (common.commit(S.exe), ("%g" % DT).replace("e-0", "e-"), "step" if EVERY == 1 else "%d steps" % EVERY,
       S.args.threads, "" if S.args.threads == 1 else "s",
       ", gravity" if extra.gravity else "",
       ("%.1f–%.1f" % (min(loads), max(loads))) if loads else "unknown", os.cpu_count()), "",
      "| model | discs | depth at %g ms (paper) | diameter | KE peaks at 0.05 / 0.10 / 0.20 / 0.30 m | "
      "delay 0.05 → 0.10 m (paper) | marked discs | wall time |" % (1e3 * END), "|---|---|---|---|---|---|---|---|"]
for r in rows:
    if "depth" not in r:
        md.append("| %s | – | failed (exit code %s) | | | | | |" % (r["model"], r["exit_code"]))
        continue
    md.append("| %s | %d | %s m (%g) | %s m | %s ms | %s ms (%s) | %d | %s min |" % (
        r["model"], r["discs"], num(r["depth"], "%.4f"), r["paper_depth"], num(r["diameter"], "%.3f"),
        " / ".join(num(r["peak_%s_ms" % c[3:]], "%.2f") for c, _ in DEPTHS), num(r["delay_ms"], "%.2f"),
        num(r["paper_delay_ms"], "%g") if math.isfinite(r["paper_delay_ms"]) else "–", r["marked"],
        num(r["wall_time_s"] / 60, "%.1f")))
S.readme_table("\n".join(md))

ok = [r for r in rows if "depth" in r]
fig, ax = plt.subplots(1, 3, figsize=(16, 4.2))
for r in ok:
    x = {"A1": 0, "A2": 1, "A3": 2, "B1": 3, "B2": 4, "C": 5}[r["model"]]
    ax[0].plot(x, r["depth"], "ko")
    ax[0].plot(x, r["paper_depth"], "rs")
ax[0].plot([], [], "ko", label="lagfsi")
ax[0].plot([], [], "rs", label="Sabatucci et al. 2013")
ax[0].axhspan(*FIELD, color="g", alpha=0.2, label="field B1a/B1b")
ax[0].set_xticks(range(6))
ax[0].set_xticklabels(["A1\n2.75e5", "A2\n2.75e4", "A3\n1.1e4", "B1\n3 mm", "B2\n6 mm", "C\n4/6 mm"])
ax[0].set_ylabel("crater depth at %g ms [m]" % (1e3 * END))
ax[0].legend(fontsize=8)
for r in ok:
    ax[1].plot([1e3 * d for _, d in DEPTHS] if False else [d for _, d in DEPTHS],
               [r["peak_%s_ms" % c[3:]] for c, _ in DEPTHS], "o-", label=r["model"])
ax[1].set_xlabel("depth [m]")
ax[1].set_ylabel("time of the KE peak [ms]")
ax[1].legend(fontsize=8)
ax[1].set_title("cf. the paper's Fig. 6")
for name, (t, kes) in series.items():
    ax[2].plot([1e3 * q for q in t], kes[0], label=name + " %.2f m" % DEPTHS[0][1])
ax[2].set_yscale("log")
ax[2].set_ylim(bottom=1e-8)
ax[2].set_xlim(0, 1e3 * min(END, 0.015))
ax[2].set_xlabel("t [ms]")
ax[2].set_ylabel("mean KE of 6 discs [J]")
ax[2].legend(fontsize=7)
fig.suptitle("dem_blast: 1 kg TNT 0.5 m above the bed, dt = %g s, shadowing every %d steps%s" %
             (DT, EVERY, ", gravity" if extra.gravity else ""))
S.figure(fig, "dem_blast.png")

if extra.no_sweep:
    S.finish([("dem_blast_runs.csv", "depth"), ("dem_blast_runs.csv", "delay_ms")])
    sys.exit(0)

# time-step sweep
w, h, end, dts = SWEEP
sweep = []
for dt in dts:
    r = S.run("dem_blast_crater/case.json", "sweep_%gx%g_%gms_dt%g" % (w, h, 1e3 * end, dt),
              sets("A2", WIDTH=w, HEIGHT=h, END=end, DT=dt, EVERY=1))
    row = {"width": w, "height": h, "end_time": end, "dt": dt, "exit_code": r.rc}
    if r.rc == 0:
        text = open(os.path.join(r.out, "crater.csv")).read()
        row["depth"] = float(re.search(r"depth = ([-0-9.eE+]+) m", text).group(1))
        b = r.summary["bodies"][0]
        row.update({"marked": b["marked_discs"], "discs": b["discs"], "wall_time_s": b["wall_time"]})
    sweep.append(row)
S.table("dem_blast_dt.csv", sweep, ["width", "height", "end_time", "dt", "exit_code", "discs", "marked", "depth",
                                    "wall_time_s"])
fig, ax = plt.subplots(figsize=(5, 3.6))
ok = [r for r in sweep if "depth" in r]
ax.semilogx([r["dt"] for r in ok], [r["depth"] for r in ok], "ko-")
ax.set_xlabel("dt [s]")
ax.set_ylabel("crater depth at %g ms [m]" % (1e3 * end))
ax.set_title("A2 law, %g m x %g m bed" % (w, h))
S.figure(fig, "dem_blast_dt.png")
S.finish([("dem_blast_runs.csv", "depth"), ("dem_blast_runs.csv", "delay_ms"), ("dem_blast_dt.csv", "depth")])
