"""A Taylor-Green vortex in a closed box of slip walls: the kinetic energy over the exact viscous decay.

u = U sin(pi x/L) cos(pi y/L), v = -U cos(pi x/L) sin(pi y/L) satisfies the Navier-Stokes equations in the box
[0, L]^2 with slip walls (no normal velocity, no shear stress), its amplitude decaying as exp(-2 nu pi^2 t / L^2)
(Taylor & Green 1937); the kinetic energy E(t) = E(0) exp(-4 nu pi^2 t / L^2). What the run loses beyond that is
numerical dissipation. Records energy_kept (E(T) / E(0) / the exact decay, at the run's end), energy_kept_half (at
T/2), area_drift (the largest |A(t)/A(0) - 1|) and elements_separated (summary.json).
Usage: /usr/bin/python3 cases/taylor_green_box/plot.py OUTDIR"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

L, NU = 0.1, 1e-5
out = out_dir_from_argv("out/taylor_green_box")
p = read_csv(os.path.join(out, "probes.csv"))
t, e = p["time"], p["kinetic_energy"]
kept = [ei / e[0] / math.exp(-4 * NU * math.pi ** 2 * ti / L ** 2) for ti, ei in zip(t, e)]
half = min(range(len(t)), key=lambda k: abs(t[k] - 0.5 * t[-1]))
area = max(abs(a / p["fluid_area"][0] - 1) for a in p["fluid_area"])
summary = json.load(open(os.path.join(out, "summary.json")))
separated = summary["bodies"][0]["remeshing"]["elements_separated"]
record("energy_kept", kept[-1])
record("energy_kept_half", kept[half])
record("area_drift", area)
record("elements_separated", separated)
print("%s: kinetic energy over the exact decay %.3f at t = %.2f s, %.3f at %.2f s; largest area drift %.1e; "
      "elements separated %d" % (os.path.basename(out.rstrip("/")), kept[-1], t[-1], kept[half], t[half], area,
                                 separated))
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(t, kept, label="lagfsi")
ax.axhline(1.0, color="k", ls="--", label="exact decay")
ax.set_xlabel("t [s]")
ax.set_ylabel("E(t) / E(0) / exp(-4 nu pi^2 t / L^2)")
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
save(fig, out)
