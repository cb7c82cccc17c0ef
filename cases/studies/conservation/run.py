"""Study: what each PFEM domain detection keeps of the fluid's area and energy, and what it costs.

Domain detections: "alpha" (the classic alpha shape, with its default "surface" volume correction), "advected" and
"level_set" (the previous mesh as the predicate, no volume correction), "advected" with 30 degrees of hysteresis
on the Delaunay flips ("keep_edges_angle": a tuned value, see the README), all with wall particles, and "advected"
with the walls as constraints on the particles on them ("wall_model": "constraints"); the advected rows join two
surfaces once their gap is below "contact_gap" h (0.3 by default), and the last row shows the constraints without
it ("contact_gap": 0, the default before), and "advected_constraints_robin" the constraints with the free surface's
Robin pressure condition ("free_surface_pressure": "robin"; the sloshing cases' own is "natural", the dam break's
"dirichlet"), and "advected_constraints_robin_particle" that with each particle keeping its own share of the area
("volume_correction": "particle", relaxation 0.02 s: a local source, not a global correction; the water's drift counts
the drops in flight, water_drift_max_pct). Flows, each at the case's own resolution, monolithic scheme:
  - sloshing_free/case_remesh.json (the first mode of a 1 m tank, h = 0.02, 10 periods): largest area drift, the
    wave's energy (kinetic + potential above the flat surface of the same area, plus viscous dissipation) at the end
    against the start, and the largest kinetic energy against the wave's energy (it is 1 for an exact solution);
  - sloshing_forced/case.json (small-amplitude shaking, h = 0.02, 6 s): the RMS error of the wall elevations
    against linear modal theory over 0-3 s and over the run, relative to the linear peak (as its plot.py), and the
    largest area drift;
  - dam_break_tank/case.json (L/20, 1 s): the energy above the rest state at 0.25 s (before the wall impact: only
    viscosity, 0.02 %, may take any), the largest area drift with the change of area split into what the remeshing
    made and what the steps made (summary.json), the front RMS against Koshizuka & Oka (pysph).
Wall times are the solver's (summary.json), one thread.
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt, read_csv  # noqa: E402

S = common.Study("conservation", __doc__.splitlines()[0])
DETECTIONS = [("alpha", {}), ("advected", {}), ("level_set", {}),
              ("advected_keep30", {"bodies.0.domain_detection": "advected", "bodies.0.keep_edges_angle": 30}),
              ("advected_constraints", {"bodies.0.domain_detection": "advected", "bodies.0.wall_model": "constraints"}),
              ("advected_constraints_gap0", {"bodies.0.domain_detection": "advected", "bodies.0.wall_model": "constraints",
                                             "bodies.0.contact_gap": 0}),
              ("advected_constraints_robin", {"bodies.0.domain_detection": "advected",
                                              "bodies.0.wall_model": "constraints",
                                              "bodies.0.scheme.free_surface_pressure": "robin"}),
              ("advected_constraints_robin_particle", {"bodies.0.domain_detection": "advected",
                                                       "bodies.0.wall_model": "constraints",
                                                       "bodies.0.scheme.free_surface_pressure": "robin",
                                                       "bodies.0.scheme.volume_correction": "particle"}),
              ("advected_constraints_robin_particle_navier", {"bodies.0.domain_detection": "advected",
                                                              "bodies.0.wall_model": "constraints",
                                                              "bodies.0.wall_friction": "navier",
                                                              "bodies.0.scheme.free_surface_pressure": "robin",
                                                              "bodies.0.scheme.volume_correction": "particle"})]
T1 = 1.18182  # the free sloshing's linear period (cases/sloshing_free)
if S.quick:   # two detections, short runs: the smoke test checks that the tables are written
    DETECTIONS = [DETECTIONS[0], DETECTIONS[-1]]
    SLOSH_END, FORCED_END, DAM_END = T1, 0.3, 0.3
else:
    SLOSH_END, FORCED_END, DAM_END = 10 * T1, 6.0, 1.0
RHO, G = 1000.0, 9.81


def settings(name, extra, flow):
    """The variant's overrides; the walls are particles unless it says otherwise (each flow keeps its walls' slip
    flag: slip in both sloshing cases, no-slip in the dam break). Every key a row does not set is pinned to the
    value the table was made with (the defaults before the monolithic scheme's became the last row's package):
    held walls, no correction but the alpha shape's surface one, and the flow's own free-surface pressure (the
    sloshing cases set "natural"; the dam break's was "dirichlet"), the analysis' Newmark (a Robin fluid's
    default integrator is now generalized-alpha) and, with particle volumes, their relaxation time of 0.02 s (the
    default is now 0.01 s)."""
    s = {"bodies.0.domain_detection": name, "bodies.0.wall_model": "particles", "bodies.0.wall_friction": "held",
         "bodies.0.scheme.volume_correction": "surface" if name == "alpha" else "none",
         "analysis.integrator.type": "newmark"}
    if flow == "dam_break_tank":
        s["bodies.0.scheme.free_surface_pressure"] = "dirichlet"
    s.update(extra)
    if s["bodies.0.scheme.volume_correction"] == "particle":
        s.setdefault("bodies.0.scheme.volume_relaxation_time", 0.02)
    return s


def energy_above_rest(p, width):
    """KE + PE - PE of the flat layer of the same area in a tank of this width, per sample."""
    return [ke + pe - RHO * G * a * a / (2 * width)
            for ke, pe, a in zip(p["kinetic_energy"], p["potential_energy"], p["fluid_area"])]


def new_row(flow, name, r):
    """The table row of run `r` (its flow, variant, exit code, solver wall time and, with probes, the time it
    reached) and its probes (None without them)."""
    row = {"flow": flow, "detection": name, "exit_code": r.rc, "wall_time_s": r.solver_wall}
    if not r.has_probes():
        return row, None
    p = r.probes()
    row["t_end"] = p["time"][-1]
    return row, p


def at(ts, ys, t):
    i = min(range(len(ts)), key=lambda k: abs(ts[k] - t))
    return ys[i]



rows, series = [], {}
ref_forced = read_csv(os.path.join(S.cases, "sloshing_forced", "reference", "linear_modal_solution.csv"))
for name, extra in DETECTIONS:
    # 1. Free sloshing, remeshed twin.
    r = S.run("sloshing_free/case_remesh.json", "sloshing_free_" + name,
              dict(settings(name, extra, "sloshing_free"), **{"analysis.end_time": SLOSH_END}), timeout=1800)
    row, p = new_row("sloshing_free", name, r)
    if p is not None:
        wave = energy_above_rest(p, 1.0)
        diss = p.get("viscous_dissipation", [0.0] * len(wave))
        row["area_drift_max_pct"] = common.area_drift(r)[1]
        row["energy_end_ratio"] = (wave[-1] + diss[-1]) / wave[0]
        row["ke_max_over_wave"] = max(p["kinetic_energy"]) / wave[0]
        series[("sloshing_free", name)] = (p["time"], [(w + d) / wave[0] for w, d in zip(wave, diss)])
    rows.append(row)
    # 2. Forced sloshing against linear theory.
    # (the wall-particle variants with no-slip walls, as the case had them when the table was made; the case
    # now has slip walls as constraints, the last variant)
    forced = dict(settings(name, extra, "sloshing_forced"), **{"analysis.end_time": FORCED_END})
    if forced["bodies.0.wall_model"] == "particles":
        forced["bodies.0.walls.0.slip"] = False
    r = S.run("sloshing_forced/case.json", "sloshing_forced_" + name, forced, timeout=1800)
    row, p = new_row("sloshing_forced", name, r)
    if p is not None:
        for col in ("eta_left", "eta_right"):
            for tag, t_end in (("3s", min(3.0, FORCED_END)), ("end", FORCED_END)):
                e2 = [(v - 0.5 - common.interp_nan(t, ref_forced["time"], ref_forced[col])) ** 2
                      for t, v in zip(p["time"], p[col]) if t <= t_end and math.isfinite(v)]
                peak = max(abs(v) for t, v in zip(ref_forced["time"], ref_forced[col]) if t <= t_end)
                row["%s_rms_%s" % (col, tag)] = math.sqrt(sum(e2) / len(e2)) / peak if e2 else float("nan")
        row["area_drift_max_pct"] = common.area_drift(r)[1]
    rows.append(row)
    # 3. Dam break in a tank: energy before the impact.
    r = S.run("dam_break_tank/case.json", "dam_break_tank_" + name,
              dict(settings(name, extra, "dam_break_tank"), **{"analysis.end_time": DAM_END}), timeout=1800)
    row, p = new_row("dam_break_tank", name, r)
    if p is not None:
        e = energy_above_rest(p, 4 * 0.146)
        row["energy_0.25s_ratio"] = at(p["time"], e, 0.25) / e[0]
        row["area_drift_max_pct"] = common.area_drift(r)[1]
        area = r.summary["bodies"][0]["fluid_area"]
        row["area_by_remeshing_pct"] = 100 * area["change_by_remeshing"] / area["initial"]
        row["area_in_steps_pct"] = 100 * area["change_in_steps"] / area["initial"]
        if "water_drift_max" in area:
            row["water_drift_max_pct"] = 100 * area["water_drift_max"]
        row.update(common.dam_break_tank_errors(r))
        series[("dam_break_tank", name)] = (p["time"], [x / e[0] for x in e])
    rows.append(row)

cols = ["flow", "detection", "exit_code", "t_end", "wall_time_s", "area_drift_max_pct", "energy_end_ratio",
        "ke_max_over_wave", "eta_left_rms_3s", "eta_right_rms_3s", "eta_left_rms_end", "eta_right_rms_end",
        "energy_0.25s_ratio", "area_by_remeshing_pct", "area_in_steps_pct", "water_drift_max_pct", "front_rms_pysph"]
S.table("conservation_runs.csv", rows, cols)

fig, axes = plt.subplots(1, 2, figsize=(13, 4.2))
for k, (flow, ax, title) in enumerate([("sloshing_free", axes[0], "free sloshing: wave energy / initial"),
                                       ("dam_break_tank", axes[1], "dam break: energy above rest / initial")]):
    for j, (name, _) in enumerate(DETECTIONS):
        if (flow, name) in series:
            t, y = series[(flow, name)]
            ax.plot(t, y, color="C%d" % j, label=name)
    ax.set_title(title)
    ax.set_xlabel("t [s]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_ylim(0, 2.0)
fig.suptitle("PFEM domain detections: energy kept (monolithic scheme, one thread)")
S.figure(fig, "conservation.png")


def f(v, fmt):
    return fmt % v if isinstance(v, float) and math.isfinite(v) else "–"


def md_table():
    out = ["| detection | free sloshing, 10 T: area drift / energy kept / KE max ÷ wave | wall s | "
           "forced sloshing: RMS 0–3 s (left / right) / 0–6 s | area drift | wall s | "
           "dam break: energy at 0.25 s / area drift (1 s) [by remeshing, in the steps] {water} / front RMS | wall s |",
           "|---" * 7 + "|"]
    by = {(r["flow"], r["detection"]): r for r in rows}
    for name, _ in DETECTIONS:
        a, b, c = by[("sloshing_free", name)], by[("sloshing_forced", name)], by[("dam_break_tank", name)]
        water = c.get("water_drift_max_pct")
        water = " {%s %%}" % f(water, "%.2f") if water is not None else ""
        out.append("| %s | %s %% / %s / %s | %s | %s / %s / %s / %s | %s %%%s | %s | %s / %s %% [%s, %s]%s / %s | %s |" % (
            name, f(a.get("area_drift_max_pct"), "%+.3f"), f(a.get("energy_end_ratio"), "%.3f"),
            f(a.get("ke_max_over_wave"), "%.2f") + failed(a), f(a["wall_time_s"], "%.0f"),
            f(b.get("eta_left_rms_3s"), "%.3f"), f(b.get("eta_right_rms_3s"), "%.3f"),
            f(b.get("eta_left_rms_end"), "%.3f"), f(b.get("eta_right_rms_end"), "%.3f"),
            f(b.get("area_drift_max_pct"), "%+.3f"), failed(b), f(b["wall_time_s"], "%.0f"),
            f(c.get("energy_0.25s_ratio"), "%.3f"), f(c.get("area_drift_max_pct"), "%+.1f"),
            f(c.get("area_by_remeshing_pct"), "%+.1f"), f(c.get("area_in_steps_pct"), "%+.1f"), water,
            f(c.get("front_rms_pysph"), "%.3f") + failed(c), f(c["wall_time_s"], "%.0f")))
    return "\n".join(out)


def failed(row):
    """A run that stopped early: its numbers cover only the part it ran."""
    return "" if row.get("exit_code") == 0 else " (**failed** at t = %s s: the numbers cover 0 to that time)" % \
        f(row.get("t_end"), "%.3f")


S.readme_table(md_table())

S.finish([("conservation_runs.csv", "area_drift_max_pct")])
