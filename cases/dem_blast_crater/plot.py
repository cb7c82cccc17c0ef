#!/usr/bin/python3
"""dem_blast_crater: kinetic energy at the four depths (0.05, 0.10, 0.20, 0.30 m below the surface, at the centre),
the times of their peaks, the crater profile, depth and diameter at the end (crater.csv), against Sabatucci et
al. (2013) and the field tests of Ambrosini et al. (2002) (B1a 0.050 m, B1b 0.045 m).

usage: /usr/bin/python3 cases/dem_blast_crater/plot.py OUTDIR
"""
import csv
import json
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from claims_record import record  # noqa: E402  (numbers for scripts/claims.py)
# the paper's crater depths [m] and KE-peak delays 0.05 -> 0.10 m [ms], by kn (4 mm discs); B1/B2 by disc size
PAPER = {2.75e5: ("A1", 0.027, 0.72), 2.75e4: ("A2", 0.053, 1.4412), 1.1e4: ("A3", 0.066, 2.2042)}
FIELD = (0.045, 0.050)
DEPTHS = [("ke_005", 0.05), ("ke_010", 0.10), ("ke_020", 0.20), ("ke_030", 0.30)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "out")
    case = json.load(open(os.path.join(out, "resolved_case.json")))
    body = case["bodies"][0]
    kn = body["contact"]["kn"]
    r = body["discs"][0]["radius"]
    summ = json.load(open(os.path.join(out, "summary.json")))
    with open(os.path.join(out, "probes.csv")) as f:
        pr = list(csv.DictReader(f))
    t = [float(p["time"]) for p in pr]
    t_end = t[-1]
    print(f"kn = {kn:g} N/m, d = {2000 * r:g} mm, dt = {body['time_step']['dt']:g} s, t_end = {1e3 * t_end:g} ms, "
          f"{summ['bodies'][0]['discs']} discs, wall time {summ['wall_time']:.0f} s on {summ['threads']} threads")
    peaks = {}
    for col, depth in DEPTHS:
        ke = [float(p[col]) for p in pr]
        i = max(range(len(ke)), key=lambda k: ke[k])
        peaks[depth] = t[i]
        record("peak_time_%03d" % round(100 * depth), t[i])
        print(f"  KE at depth {depth:.2f} m: peak {ke[i]:.4g} J at {1e3 * t[i]:.3f} ms")
    delay = 1e3 * (peaks[0.10] - peaks[0.05])
    record("delay_ms", delay)
    name, depth_ref, delay_ref = PAPER.get(kn, ("?", float("nan"), float("nan")))
    print(f"  KE-peak delay 0.05 -> 0.10 m: {delay:.3f} ms (paper {name}: {delay_ref} ms)")
    text = open(os.path.join(out, "crater.csv")).read()
    m = re.search(r"depth = ([-0-9.eE+]+) m .*diameter = ([-0-9.eE+]+) m", text)
    depth, diam = float(m.group(1)), float(m.group(2))
    record("depth", depth)
    record("diameter", diam)
    record("blast_work", float(pr[-1]["blast_work"]))
    print(f"  crater at {1e3 * t_end:g} ms: depth {depth:.4f} m (paper {name}: {depth_ref} m; field tests "
          f"{FIELD[0]}-{FIELD[1]} m), diameter {diam:.3f} m (not reported by the paper; D = 0.8 W^(1/3) = 0.8 m "
          f"for a surface burst)")
    with open(os.path.join(out, "crater.csv")) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    xs = [float(q["x"]) for q in rows]
    hs = [float(q["surface"]) for q in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4))
    for col, depth in DEPTHS:
        a1.plot([1e3 * x for x in t], [float(p[col]) for p in pr], label=f"{depth:.2f} m")
    a1.set_xlim(0, 15)
    a1.set_xlabel("t [ms]")
    a1.set_ylabel("mean KE of 6 discs [J]")
    a1.set_yscale("log")
    a1.set_ylim(bottom=1e-8)
    a1.legend(title="depth")
    a2.plot(xs, hs, "k-", label=f"surface at {1e3 * t_end:g} ms")
    surf = max(hs) if not hs else None
    a2.axhline(0.4266, color="0.5", ls=":", label="initial surface")
    a2.axhline(0.4266 - depth_ref, color="r", ls="--", lw=0.8, label=f"paper {name} depth")
    a2.axhspan(0.4266 - FIELD[1], 0.4266 - FIELD[0], color="g", alpha=0.2, label="field tests")
    a2.set_xlabel("x [m]")
    a2.set_ylabel("surface [m]")
    a2.set_ylim(0.3, 0.45)
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "comparison.png"), dpi=110)  # (the README's copy is the full run's, copied by hand)


if __name__ == "__main__":
    main()
