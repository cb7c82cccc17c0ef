"""Study 1: accuracy against wall time of the two fluid schemes on the two dam breaks.

dam_break_tank (Koshizuka & Oka 1996) and dam_break_floor/case_remesh.json (Martin & Moyce 1952, PFEM
remeshing) at h = L/20, L/40, L/80 with both fluid schemes (bodies.0.scheme.type = monolithic_pspg,
fractional_step) and two time steps per h: the stability limit dt_lim(h) (stability_map study: 1 ms at L/20
on the tank, 2 ms fails; dt scaled with h) and dt_lim/2. Per run: the solver's wall time (one thread), the
front RMS error against the experiment (as the cases' plot.py), the wall-impact time error (tank), the
column-height RMS (floor), the fluid-area drift. Chart: error against wall time (log-log), one line per scheme
through its own Pareto-optimal runs, the overall Pareto front ringed.

Shortened runs (the measures need no more): the tank to 0.35 s (the front error is measured up to the wall,
impact at about 0.26 s), the floor to 0.17 s (T = t sqrt(2g/a) = 3.15; the front error is measured for T <= 3).
Full mode leaves out the costliest runs (dt_lim/2 at the finest h; the monolithic scheme at h/80) and adds
L/160 on the tank for the fractional step only (killed after 20 minutes): see
README.md. Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

S = common.Study("accuracy_walltime", __doc__.splitlines()[0])
# Series: the two schemes with the alpha shape, wall particles and the surface correction (as the tables were
# first measured: the monolithic scheme's defaults before its conservative defaults, the fractional step's
# still), and the monolithic scheme with its defaults now (series "package": the advected domain, walls as constraints
# with Navier friction, the Robin surface, particle volumes and generalized-alpha).
SCHEMES = ["monolithic_pspg", "fractional_step", "package"]
COLORS = {"monolithic_pspg": "C0", "fractional_step": "C1", "package": "C2"}
SCHEME_TYPE = {"monolithic_pspg": "monolithic_pspg", "fractional_step": "fractional_step", "package": "monolithic_pspg"}
L_TANK, A_FLOOR = 0.146, 0.05715

if S.quick:
    plan = {"tank": [(10, 1.0), (20, 1.0)], "floor": [(10, 1.0), (20, 1.0)]}
    skip = set()
else:
    plan = {"tank": [(20, 1.0), (20, 0.5), (40, 1.0), (40, 0.5), (80, 1.0), (160, 1.0)],
            "floor": [(20, 1.0), (20, 0.5), (40, 1.0), (40, 0.5), (80, 1.0)]}
    # The monolithic scheme's direct solve grows like N^2 (about 2 s a step at L/80): left out, see README.md.
    skip = {(flow, scheme, n, 1.0) for flow in ("tank", "floor") for scheme in ("monolithic_pspg", "package")
            for n in (80, 160)}

# The alpha shape with wall particles and the surface correction, as the tables were measured: the monolithic
# scheme's default before its conservative defaults (docs/decisions/0001-0006; the fractional step's still;
# cases/studies/conservation compares the domain detections).
BASE = {"output.vtk": False, "bodies.0.domain_detection": "alpha"}


def settings(scheme, extra):
    """The run's overrides: the series' scheme, the alpha shape unless the series is "package" (the defaults)."""
    s = dict(BASE, **extra)
    s["bodies.0.scheme.type"] = SCHEME_TYPE[scheme]
    if scheme == "package":
        del s["bodies.0.domain_detection"]
    return s


def run_row(r, scheme, h, h_label, dt, f, errors):
    """One table row of a run: its set-up, outcome, cost, errors against the experiment and area drift."""
    row = {"_run": r, "scheme": scheme, "h": h, "h_label": h_label, "dt": dt, "dt_factor": f, "exit_code": r.rc,
           "status": r.summary.get("status", "?"), "t_end": r.summary.get("time", float("nan")),
           "wall_time_s": r.solver_wall, "steps": r.summary.get("steps", 0),
           "step_retries": r.summary.get("step_retries", 0),
           "particles": (r.summary.get("bodies") or [{}])[0].get("nodes", 0)}
    if r.has_probes():
        row.update(errors(r))
        row["area_drift_end_pct"], row["area_drift_max_pct"] = common.area_drift(r)
        # The water (mesh + drops in flight) where the run keeps particle volumes (series "package"); the mesh's area
        # otherwise (the alpha shape's surface correction holds it).
        area = ((r.summary.get("bodies") or [{}])[0]).get("fluid_area", {})
        w = area.get("water_drift_max")
        row["water_drift_max_pct"] = 100 * w if w is not None else abs(row["area_drift_max_pct"])
    return row


rows = {"tank": [], "floor": []}
for scheme in SCHEMES:
    for n, f in plan["tank"]:
        h = L_TANK / n
        dt = 1e-3 * (20.0 / n) * f  # stability limit 1 ms at L/20, scaled with h
        if ("tank", scheme, n, f) in skip:
            continue
        r = S.run("dam_break_tank/case.json", "tank_%s_L%d_dt%.3g" % (scheme, n, dt),
                  settings(scheme, {"analysis.end_time": 0.35, "analysis.dt": dt, "bodies.0.spacing": h}),
                  timeout=1200 if n >= 160 else 1500)
        rows["tank"].append(run_row(r, scheme, h, "L/%d" % n, dt, f, common.dam_break_tank_errors))
    for n, f in plan["floor"]:
        h = A_FLOOR / n
        dt = 5e-4 * (20.0 / n) * f  # the case's 0.5 ms at a/20 (the same dt sqrt(g/a) as the tank)
        if ("floor", scheme, n, f) in skip:
            continue
        r = S.run("dam_break_floor/case_remesh.json", "floor_%s_a%d_dt%.3g" % (scheme, n, dt),
                  settings(scheme, {"analysis.end_time": 0.17, "analysis.dt": dt, "bodies.0.spacing": h}),
                  timeout=1500)
        rows["floor"].append(run_row(r, scheme, h, "a/%d" % n, dt, f, common.dam_break_floor_errors))



def self_error(rs, length, scale, t_max):
    """Discretization error without the experiment: RMS of Z(t) - Z_ref(t) over the reference run's samples with
    T = t*scale <= t_max, Z = front_x/length, the reference being the completed run with the smallest h, then dt
    (of either scheme). Stored as front_rms_vs_finest; the reference row gets NaN."""
    done = [r for r in rs if r["exit_code"] == 0]
    if not done:
        return None
    ref = min(done, key=lambda r: (r["h"], r["dt"]))
    pr = ref["_run"].probes()
    samples = [(t, x / length) for t, x in zip(pr["time"], pr["front_x"]) if t * scale <= t_max]
    for r in rs:
        if r is ref or r["exit_code"] != 0:
            r["front_rms_vs_finest"] = float("nan")
            continue
        p = r["_run"].probes()
        e = [common.interp_nan(t, p["time"], [x / length for x in p["front_x"]]) - z for t, z in samples]
        e = [x for x in e if math.isfinite(x)]
        r["front_rms_vs_finest"] = math.sqrt(sum(x * x for x in e) / len(e)) if e else float("nan")
    return "%s %s dt %.3g ms" % (ref["scheme"], ref["h_label"], 1e3 * ref["dt"])


ref_tank = self_error(rows["tank"], L_TANK, math.sqrt(2 * 9.81 / L_TANK), 3.0)
ref_floor = self_error(rows["floor"], A_FLOOR, math.sqrt(2 * 9.81 / A_FLOOR), 3.0)
tank_cols = ["scheme", "h_label", "h", "dt", "dt_factor", "exit_code", "status", "t_end", "wall_time_s", "steps",
             "step_retries", "particles", "front_rms_pysph", "front_rms_dsph", "impact_time", "impact_error",
             "area_drift_end_pct", "area_drift_max_pct", "water_drift_max_pct", "front_rms_vs_finest"]
floor_cols = ["scheme", "h_label", "h", "dt", "dt_factor", "exit_code", "status", "t_end", "wall_time_s", "steps",
              "step_retries", "particles", "front_rms", "height_rms", "area_drift_end_pct", "area_drift_max_pct",
              "water_drift_max_pct", "front_rms_vs_finest"]
S.table("tank_runs.csv", rows["tank"], tank_cols)
S.table("floor_runs.csv", rows["floor"], floor_cols)


def chart(ax, rs, key, ylabel, absval=False):
    """Error against wall time, one line per scheme through its Pareto-optimal runs, overall front ringed."""
    ok = [r for r in rs if r["exit_code"] == 0 and math.isfinite(r.get(key, float("nan")))]
    pts = [(r["wall_time_s"], abs(r[key]) if absval else r[key]) for r in ok]
    for scheme in SCHEMES:
        sel = [i for i, r in enumerate(ok) if r["scheme"] == scheme]
        if not sel:
            continue
        ax.plot([pts[i][0] for i in sel], [pts[i][1] for i in sel], "o", color=COLORS[scheme], ms=6,
                label=scheme)
        own = common.pareto([pts[i] for i in sel])
        ax.plot([pts[sel[i]][0] for i in own], [pts[sel[i]][1] for i in own], "-", color=COLORS[scheme], lw=1.2)
        for i in sel:
            ax.annotate("%s, dt %.3gms" % (ok[i]["h_label"], 1e3 * ok[i]["dt"]), pts[i], fontsize=6,
                        xytext=(3, 3), textcoords="offset points")
    front = common.pareto(pts)
    ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "o", mfc="none", mec="k", ms=12,
            label="Pareto front (all series)")
    failed = [r for r in rs if r["exit_code"] != 0]
    for r in failed:
        ax.axvline(r["wall_time_s"], color=COLORS[r["scheme"]], ls=":", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time [s] (1 thread)")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)


fig, axes = plt.subplots(2, 2, figsize=(14, 10))
axes = axes.ravel()
chart(axes[3], rows["tank"], "front_rms_vs_finest", "front RMS in Z against the finest run (T <= 3)")
axes[3].set_title("discretization error (reference: %s)" % ref_tank, fontsize=9)
chart(axes[0], rows["tank"], "front_rms_pysph", "front RMS in Z (pysph digitization)")
chart(axes[1], rows["tank"], "impact_error", "|impact time - 0.30 s| [s]", absval=True)
chart(axes[2], rows["tank"], "water_drift_max_pct", "largest |drift| of the water [%] (to 0.35 s)", absval=True)
axes[0].set_title("dam_break_tank: front error vs wall time")
axes[1].set_title("impact time error (experiment 0.30 s)")
axes[2].set_title("water drift (mesh + drops in flight with particle volumes; the mesh's area otherwise)",
                  fontsize=9)
S.figure(fig, "tank_error_vs_walltime.png")

fig, axes = plt.subplots(2, 2, figsize=(14, 10))
axes = axes.ravel()
chart(axes[3], rows["floor"], "front_rms_vs_finest", "front RMS in Z against the finest run (T <= 3)")
axes[3].set_title("discretization error (reference: %s)" % ref_floor, fontsize=9)
chart(axes[0], rows["floor"], "front_rms", "front RMS in Z, T <= 3 (Martin & Moyce)")
chart(axes[1], rows["floor"], "height_rms", "column height RMS in H")
chart(axes[2], rows["floor"], "water_drift_max_pct", "largest |drift| of the water [%] (to 0.17 s)", absval=True)
axes[0].set_title("dam_break_floor (remeshed): front error vs wall time")
axes[1].set_title("column height error")
axes[2].set_title("water drift (mesh + drops in flight with particle volumes; the mesh's area otherwise)",
                  fontsize=9)
S.figure(fig, "floor_error_vs_walltime.png")

S.finish([("tank_runs.csv", "wall_time_s"), ("tank_runs.csv", "front_rms_pysph"),
          ("floor_runs.csv", "wall_time_s"), ("floor_runs.csv", "front_rms")])
