"""Study 3: stability maps.

Fluid: cases/dam_break_tank (0.5 s: the surge, the wall impact at 0.26 s and the run-up) for each fluid scheme
on an (h, dt) grid, without step halving (analysis.max_step_halvings = 0, so that a failed step ends the run
instead of being retried at dt/2, as the case's default 4 halvings would). Each run is classed as
  stable             completed, largest |area drift| <= 5 %, kinetic energy below the potential energy released
                     by the collapse of the column (61 J per metre; an energy probe is added for this);
  area blow-up       completed, |area drift| > 5 %;
  energy blow-up     completed, kinetic energy above that bound;
  tangling           exit code 3 on an element turned inside out (particle tangling);
  non-convergent     exit code 3 on Newton (or another solver) not converging.
Solid: cases/turek_csm3 (5 s) with Newmark (1/4, 1/2) against generalized-alpha (rho_inf 0.8 and 0.5) at large
dt; the energy probe "balance" (E - E0 - W_gravity, zero for an exact integrator) relative to the largest
mechanical energy shows growth (> 0) or numerical dissipation (< 0).
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

S = common.Study("stability_map", __doc__.splitlines()[0])
L = 0.146
U = math.sqrt(2 * 9.81 * 2 * L)  # free-fall speed of the column height: the surge speed scale, 2.4 m/s
KE_BOUND = 1000 * 9.81 * L * 2 * L * L  # potential energy of the column above its final level (< rho g A H/2)
SCHEMES = ["monolithic_pspg", "fractional_step"]
END = 0.3 if S.quick else 0.5
if S.quick:
    GRID = {10: [1e-3, 2e-3, 4e-3], 20: [1e-3, 2e-3]}
    SCHEMES = ["fractional_step"]
else:
    GRID = {10: [5e-4, 1e-3, 2e-3, 4e-3, 8e-3], 20: [2.5e-4, 5e-4, 1e-3, 1.5e-3, 2e-3, 4e-3],
            40: [1.25e-4, 2.5e-4, 5e-4, 1e-3, 2e-3]}
SKIP = set() if S.quick else {("monolithic_pspg", 40, 1.25e-4)}  # about 10 min alone; see README.md
PROBES = [{"name": "front_x", "type": "front", "body": "water", "floor": 0.0},
          {"name": "fluid_area", "type": "fluid_area", "body": "water"},
          {"name": "kinetic_energy", "type": "kinetic_energy", "body": "water"}]


def classify(r):
    m = r.message.lower()
    if r.rc == 3:
        if "inside out" in m or "inverted" in m:
            return "tangling"
        return "non-convergent"
    if r.rc != 0:
        return "error %d" % r.rc
    drift = common.area_drift(r)[1]
    ke = max(r.probes()["kinetic_energy"])
    if ke > KE_BOUND:
        return "energy blow-up"
    if abs(drift) > 5.0:
        return "area blow-up"
    return "stable"


rows = []
for scheme in SCHEMES:
    for n, dts in GRID.items():
        for dt in dts:
            if (scheme, n, dt) in SKIP:
                continue
            h = L / n
            r = S.run("dam_break_tank/case.json", "tank_%s_L%d_dt%g" % (scheme, n, dt),
                      {"output.vtk": False, "analysis.end_time": END, "analysis.dt": dt,
                       "analysis.max_step_halvings": 0, "bodies.0.spacing": h, "bodies.0.scheme.type": scheme,
                       "bodies.0.domain_detection": "alpha",
                       "probes": PROBES}, timeout=900)
            row = {"scheme": scheme, "h": h, "h_label": "L/%d" % n, "dt": dt, "courant": U * dt / h,
                   "exit_code": r.rc, "class": classify(r), "t_reached": r.summary.get("time", float("nan")),
                   "wall_time_s": r.solver_wall, "message": r.message[:160] if r.rc else ""}
            if r.has_probes():
                row["area_drift_max_pct"] = common.area_drift(r)[1]
                row["kinetic_energy_max"] = max(r.probes()["kinetic_energy"])
            rows.append(row)
S.table("fluid_map.csv", rows, ["scheme", "h_label", "h", "dt", "courant", "exit_code", "class", "t_reached",
                                "wall_time_s", "area_drift_max_pct", "kinetic_energy_max", "message"])

STYLE = {"stable": ("o", "tab:green"), "area blow-up": ("s", "tab:orange"), "energy blow-up": ("^", "tab:purple"),
         "tangling": ("X", "tab:red"), "non-convergent": ("D", "tab:brown")}
fig, axes = plt.subplots(1, len(SCHEMES), figsize=(6.5 * len(SCHEMES), 5), squeeze=False)
for ax, scheme in zip(axes[0], SCHEMES):
    sel = [r for r in rows if r["scheme"] == scheme]
    for cls, (mk, col) in STYLE.items():
        pts = [r for r in sel if r["class"] == cls]
        if pts:
            ax.plot([r["h"] for r in pts], [r["dt"] for r in pts], mk, color=col, ms=11, label=cls, ls="none")
    for r in sel:
        if r["class"] != "stable":
            ax.annotate("t=%.2f" % r["t_reached"] if r["exit_code"] else "%+.0f%%" % r["area_drift_max_pct"],
                        (r["h"], r["dt"]), fontsize=6, xytext=(6, -3), textcoords="offset points")
    hs = [L / 80, L / 5]
    for c in (0.25, 0.5, 1.0):
        ax.plot(hs, [c * h / U for h in hs], ":", color="0.5", lw=0.8)
        ax.text(hs[1] * 0.55, c * hs[1] * 0.55 / U, "U dt/h = %g" % c, fontsize=7, color="0.4")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(L / 60, L / 7)
    ax.set_ylim(1e-4, 1.2e-2)
    ax.set_xlabel("particle spacing h [m]")
    ax.set_ylabel("dt [s]")
    ax.set_title("dam_break_tank, %s, %.1f s, no step halving" % (scheme, END), fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left")
S.figure(fig, "fluid_stability_map.png")

# ----------------------------------------------------------------------------------------------- solid
SOLID_END = 3.0 if S.quick else 5.0
SDTS = [0.05, 0.1] if S.quick else [0.005, 0.02, 0.05, 0.1, 0.2]
INTEGRATORS = {"newmark": {"type": "newmark", "beta": 0.25, "gamma": 0.5},
               "gen_alpha_0.8": {"type": "generalized_alpha", "rho_inf": 0.8},
               "gen_alpha_0.5": {"type": "generalized_alpha", "rho_inf": 0.5}}
if S.quick:
    INTEGRATORS.pop("gen_alpha_0.5")
srows, sseries = [], {}


def period_amplitudes(t, u):
    """(max - min)/2 of u over each full period between successive upward crossings of the mid-level."""
    mid = 0.5 * (max(u) + min(u))
    ups = [i for i in range(1, len(u)) if u[i - 1] < mid <= u[i]]
    return [0.5 * (max(u[a:b + 1]) - min(u[a:b + 1])) for a, b in zip(ups, ups[1:])]


for name, integ in INTEGRATORS.items():
    for dt in SDTS:
        r = S.run("turek_csm3/case.json", "csm3_%s_dt%g" % (name, dt),
                  {"output.vtk": False, "analysis.end_time": SOLID_END, "analysis.dt": dt,
                   "analysis.max_step_halvings": 0, "analysis.integrator": integ,
                   "probes": [{"name": "tip_uy", "type": "displacement", "body": "flag", "at": [0.6, 0.2],
                               "component": "y"},
                              {"name": "balance", "type": "energy", "body": "flag", "kind": "balance"},
                              {"name": "work", "type": "energy", "body": "flag", "kind": "external_work"},
                              {"name": "total", "type": "energy", "body": "flag", "kind": "total"}]},
                  timeout=600)
        row = {"integrator": name, "dt": dt, "period_fraction": dt * 1.0995, "exit_code": r.rc,
               "t_reached": r.summary.get("time", float("nan")), "wall_time_s": r.solver_wall,
               "message": r.message[:160] if r.rc else ""}
        if r.has_probes():
            p = r.probes()
            emax = max(max(abs(w) for w in p["work"]), 1e-300)
            rel = [b / emax for b in p["balance"]]
            row["energy_balance_end_rel"] = rel[-1]
            row["energy_balance_maxabs_rel"] = max(rel, key=abs)
            s = common.lagfsi_post.last_period_stats(p["time"], p["tip_uy"])
            if s:
                row["uy_amplitude"], row["frequency"] = s["amplitude"], s["frequency"]
            amps = period_amplitudes(p["time"], p["tip_uy"])
            if len(amps) >= 2:
                row["periods"] = len(amps)
                row["amplitude_ratio_last_first"] = amps[-1] / amps[0]
            sseries[(name, dt)] = (p["time"], rel, p["tip_uy"])
        # Classed on the tip amplitude (energy ~ amplitude^2): at large dt the end-of-step energy of
        # generalized-alpha jumps between steps (README.md), so the balance is only a measure for Newmark here.
        ar = row.get("amplitude_ratio_last_first", 1.0)
        row["class"] = ("non-convergent" if r.rc == 3 else "error" if r.rc else
                        "growth" if ar > 1.01 else "decay" if ar < 0.99 else "conservative (1 %)")
        srows.append(row)
S.table("solid_integrators.csv", srows, ["integrator", "dt", "period_fraction", "exit_code", "class", "t_reached",
                                         "wall_time_s", "periods", "amplitude_ratio_last_first",
                                         "energy_balance_end_rel", "energy_balance_maxabs_rel", "uy_amplitude",
                                         "frequency", "message"])

fig, axes = plt.subplots(1, 3, figsize=(17, 4.6))
for k, name in enumerate(INTEGRATORS):
    sel = [r for r in srows if r["integrator"] == name and "energy_balance_end_rel" in r]
    sel = [r for r in sel if "amplitude_ratio_last_first" in r and r["exit_code"] == 0]
    axes[0].plot([r["dt"] for r in sel], [r["amplitude_ratio_last_first"] for r in sel], "o-", color="C%d" % k,
                 label=name)
    bad = [r for r in srows if r["integrator"] == name and r["exit_code"] != 0]
    axes[0].plot([r["dt"] for r in bad], [r.get("amplitude_ratio_last_first", 1.0) for r in bad], "x",
                 color="C%d" % k, ms=12, mew=2)
    for j, dt in enumerate(SDTS):
        if (name, dt) in sseries and k < 2:
            t, rel, uy = sseries[(name, dt)]
            axes[1 + k].plot(t, rel, color=plt.cm.viridis(j / max(len(SDTS) - 1, 1)), label="dt = %g s" % dt)
axes[0].axhline(1, color="k", lw=0.6)
axes[0].set_xscale("log")
axes[0].set_xlabel("dt [s] (first period 0.91 s)")
axes[0].set_ylabel("tip u_y amplitude, last period / first period")
axes[0].set_title("CSM3, %.0f s: amplitude growth (> 1) or decay (< 1); x: failed run\n"
                  "(at its ratio up to the failure, or at 1 if less than 2 periods)" % SOLID_END, fontsize=9)
for ax, name in zip(axes[1:], list(INTEGRATORS)[:2]):
    ax.set_title("energy probe balance (E - E0 - W) / max W, %s" % name, fontsize=9)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("relative energy error")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
S.figure(fig, "solid_energy.png")

S.finish([("fluid_map.csv", "exit_code"), ("fluid_map.csv", "t_reached"), ("solid_integrators.csv", "t_reached")])
