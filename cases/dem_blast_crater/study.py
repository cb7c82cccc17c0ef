#!/usr/bin/python3
"""dem_blast_crater study: crater depth against the normal stiffness kn (models A1, A2, A3: 4 mm discs, kn =
2.75e5, 2.75e4, 1.1e4 N/m) and against the disc size (B1 3 mm, A2 4 mm, B2 6 mm at kn = 2.75e4), as Sabatucci et
al. (2013) Tables 3-4 and Fig. 6; writes study.csv and study.png in OUTDIR.

The paper's runs take dt = 1e-7 s and 40 ms (4e5 steps); --dt and --end-time run a cheaper version (the critical
step of the stiffest branch lambda^2 kn is 2.1e-5 s for A2 and 6.8e-6 s for A1, so dt = 1e-6 s is within it), and
--exposure-every recomputes the blast shadowing every N steps instead of every step.

usage: /usr/bin/python3 cases/dem_blast_crater/study.py OUTDIR [--exe build/lagfsi] [--dt 1e-7] [--end-time 0.04]
       [--exposure-every 1] [--threads 2] [--only A1,A2,...]
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
# model: (kn, disc radius, paper depth [m], paper delay 0.05 -> 0.10 m [ms])
MODELS = {"A1": (2.75e5, 0.002, 0.027, 0.72), "A2": (2.75e4, 0.002, 0.053, 1.4412), "A3": (1.1e4, 0.002, 0.066, 2.2042),
          "B1": (2.75e4, 0.0015, 0.054, None), "B2": (2.75e4, 0.003, 0.053, None)}


def run(exe, out, name, kn, r, a):
    d = os.path.join(out, name)
    sets = [f"bodies.0.contact.kn={kn}", f"bodies.0.discs.0.radius={r}", f"bodies.0.time_step.dt={a.dt}",
            f"analysis.end_time={a.end_time}", f"bodies.0.blast.exposure_every={a.exposure_every}"]
    if not os.path.exists(os.path.join(d, "summary.json")) or a.rerun:
        cmd = [exe, "run", os.path.join(HERE, "case.json"), "-o", d, "--quiet", "--threads", str(a.threads)]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True)
    with open(os.path.join(d, "probes.csv")) as f:
        pr = list(csv.DictReader(f))
    t = [float(p["time"]) for p in pr]
    peak = {}
    for col in ("ke_005", "ke_010"):
        ke = [float(p[col]) for p in pr]
        peak[col] = t[max(range(len(ke)), key=lambda k: ke[k])]
    text = open(os.path.join(d, "crater.csv")).read()
    m = re.search(r"depth = ([-0-9.eE+]+) m .*diameter = ([-0-9.eE+]+) m", text)
    return float(m.group(1)), float(m.group(2)), 1e3 * (peak["ke_010"] - peak["ke_005"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "lagfsi"))
    ap.add_argument("--dt", type=float, default=1e-7)
    ap.add_argument("--end-time", type=float, default=0.04)
    ap.add_argument("--exposure-every", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", default=",".join(MODELS))
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    rows = []
    for name in a.only.split(","):
        kn, r, depth_ref, delay_ref = MODELS[name]
        depth, diam, delay = run(a.exe, a.outdir, name, kn, r, a)
        rows.append((name, kn, 2 * r, depth, depth_ref, diam, delay, delay_ref))
        print(f"{name}: kn {kn:g}, d {2000 * r:g} mm: crater depth {depth:.4f} m (paper {depth_ref}), diameter "
              f"{diam:.3f} m, KE-peak delay 0.05->0.10 m {delay:.3f} ms (paper {delay_ref})", flush=True)
    with open(os.path.join(a.outdir, "study.csv"), "w") as f:
        f.write(f"# dt = {a.dt} s, end time {a.end_time} s, exposure every {a.exposure_every} steps\n")
        f.write("model,kn,d,depth,paper_depth,diameter,ke_peak_delay_ms,paper_delay_ms\n")
        for row in rows:
            f.write(",".join(str(v) for v in row) + "\n")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for name, kn, d, depth, ref, *_ in rows:
        ax = a1 if name.startswith("A") else a2
        x = kn if ax is a1 else 1e3 * d
        ax.plot(x, depth, "ko")
        ax.plot(x, ref, "rs")
        if name == "A2":
            a2.plot(1e3 * d, depth, "ko")
            a2.plot(1e3 * d, ref, "rs")
    a1.set_xscale("log")
    a1.set_xlabel("kn [N/m]")
    a2.set_xlabel("disc diameter [mm]")
    for ax in (a1, a2):
        ax.set_ylabel("crater depth [m]")
        ax.axhspan(0.045, 0.050, color="g", alpha=0.2)
    a1.plot([], [], "ko", label="lagfsi")
    a1.plot([], [], "rs", label="Sabatucci et al. 2013")
    a1.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.outdir, "study.png"), dpi=110)


if __name__ == "__main__":
    main()
