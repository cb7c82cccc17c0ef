"""Study: wall loads and run-up against CPU time, the fluid's settings on the dam break against a pressure-sensor wall.

cases/dam_break_pressure (Zhou, De Kat & Buchner 1999; Buchner 2002; the converged delta-SPH of Marrone et al. 2011) at
H/dx = 10, 20, 40 (spacing 0.06, 0.03, 0.015 m; the case's dt = 1 ms, 1.6 s of flow) with five settings: the monolithic
scheme's defaults ("package": the advected domain, walls as constraints sliding against their Navier friction, the Robin
surface, particle volumes), the same with held (no-slip) walls, the monolithic scheme with the classic settings (the
alpha shape, wall particles), the fractional step with its classic defaults, and the fractional step with the
conservative preset. Per run: the CPU time, and the error measures of the case's README (cases/tools/wall_pressure.py):
the impact time at P1 and the quasi-static plateau against the experiment, the pressure impulse of the first 0.1 s
against the delta-SPH, the time the run-up wets P2 against the experiment, the highest run-up on the wall and the
largest share of the water above 2 H. Chart: each measure against CPU time, one line per setting through its own
Pareto-optimal runs. Quick mode: H/dx = 10 only, to t* = 5.1 (1.25 s).
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import common  # noqa: E402
from common import plt  # noqa: E402
import wall_pressure as wp  # noqa: E402

S = common.Study("wall_pressure", __doc__.splitlines()[0])
SERIES = {
    "package": {},
    "package, held walls": {"bodies.0.wall_friction": "held"},
    "monolithic, classic": {"bodies.0.preset": "classic"},
    "fractional, classic": {"bodies.0.scheme.type": "fractional_step"},
    "fractional, conservative": {"bodies.0.scheme.type": "fractional_step", "bodies.0.preset": "conservative"},
}
COLORS = dict(zip(SERIES, ["C0", "C1", "C2", "C3", "C4"]))
H = 0.6
LEVELS = [10] if S.quick else [10, 20, 40]
END = 1.25 if S.quick else 1.6
REF = wp.reference_measures()
FLOOR = 1e-4  # a measure of zero (no water above 2 H) drawn here on the log scale


def rel(value, reference):
    return value / reference - 1 if math.isfinite(value) else float("nan")


rows = []
for name, sets in SERIES.items():
    for n in LEVELS:
        tag = "%s_H%d" % (name.replace(", ", "_").replace(" ", "_"), n)
        r = S.run("dam_break_pressure/case.json", tag,
                  dict(sets, **{"bodies.0.spacing": H / n, "analysis.end_time": END, "output.vtk": False}),
                  timeout=1800)
        row = {"series": name, "H_dx": n, "exit_code": r.rc, "status": r.summary.get("status", "?"),
               "cpu_s": r.cpu if r.cpu is not None else r.wall, "steps": r.summary.get("steps", 0),
               "step_retries": r.summary.get("step_retries", 0)}
        if r.has_probes():
            m = wp.measures(r.probes())
            row.update({"impact": m["onset"], "impact_error": rel(m["onset"], REF["exp_onset"]),
                        "plateau": m["plateau"], "plateau_error": rel(m["plateau"], REF["exp_plateau"]),
                        "impulse": m["impulse"], "impulse_error_sph": rel(m["impulse"], REF["sph_impulse"]),
                        "p2_wets": m["p2_wets"], "p2_wets_error": rel(m["p2_wets"], REF["exp_p2_wets"]),
                        "runup_max_m": m["runup_max"], "above_2H_max_pct": 100 * m["above_2H_max"]})
        rows.append(row)

cols = ["series", "H_dx", "exit_code", "status", "cpu_s", "steps", "step_retries", "impact", "impact_error", "plateau",
        "plateau_error", "impulse", "impulse_error_sph", "p2_wets", "p2_wets_error", "runup_max_m", "above_2H_max_pct"]
S.table("runs.csv", rows, cols)


def chart(ax, key, ylabel, target=None):
    """|measure| against CPU time (log-log; a zero drawn at FLOOR), one line per setting through its Pareto-optimal
    runs; the target dashed."""
    for name in SERIES:
        pts = [(r["cpu_s"], max(abs(r[key]), FLOOR)) for r in rows
               if r["series"] == name and r["exit_code"] == 0 and math.isfinite(r.get(key, float("nan")))]
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", color=COLORS[name], label=name)
        front = sorted(pts[i] for i in common.pareto(pts))
        ax.plot([p[0] for p in front], [p[1] for p in front], "-", color=COLORS[name], lw=1)
        for (c, v), r in zip(pts, [r for r in rows if r["series"] == name and r["exit_code"] == 0
                                   and math.isfinite(r.get(key, float("nan")))]):
            ax.annotate("H/dx %d" % r["H_dx"], (c, v), fontsize=6, xytext=(3, 3), textcoords="offset points")
    if target:
        ax.axhline(target, color="k", ls="--", lw=0.8, label="target")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time [s] (1 thread)")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)


fig, axes = plt.subplots(2, 3, figsize=(16, 9))
axes = axes.ravel()
chart(axes[0], "impact_error", "|impact at P1 / experiment - 1|", 0.03)
chart(axes[1], "plateau_error", "|P1 plateau / experiment - 1|", 0.10)
chart(axes[2], "impulse_error_sph", "|P1 impulse (0.1 s) / delta-SPH - 1|", 0.15)
chart(axes[3], "p2_wets_error", "|run-up wets P2 / experiment - 1|", 0.15)
chart(axes[4], "runup_max_m", "highest run-up on the wall [m]")
chart(axes[5], "above_2H_max_pct", "largest share of the water above 2 H [%]", 0.5)
fig.suptitle("dam_break_pressure: wall loads and run-up against CPU time (H/dx = %s)" % ", ".join(map(str, LEVELS)))
S.figure(fig, "error_vs_cpu.png")


def fmt(v, spec):
    return spec % v if isinstance(v, float) and math.isfinite(v) else "–"


lines = ["| setting | H/dx | CPU s | retried steps | impact | plateau | impulse (δ-SPH) | P2 wetted | run-up m | "
         "above 2 H |", "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s |" % (
        r["series"], r["H_dx"], fmt(r["cpu_s"], "%.1f"), r["step_retries"], fmt(100 * r.get("impact_error", float("nan")), "%+.1f %%"),
        fmt(100 * r.get("plateau_error", float("nan")), "%+.1f %%"),
        fmt(100 * r.get("impulse_error_sph", float("nan")), "%+.1f %%"),
        fmt(100 * r.get("p2_wets_error", float("nan")), "%+.1f %%"), fmt(r.get("runup_max_m"), "%.2f"),
        fmt(r.get("above_2H_max_pct"), "%.2f %%")))
S.readme_table("\n".join(lines))
S.finish([("runs.csv", "cpu_s"), ("runs.csv", "impact"), ("runs.csv", "above_2H_max_pct")])
