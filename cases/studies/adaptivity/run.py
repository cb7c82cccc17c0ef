"""Study: what an adaptive particle size and an adaptive time step buy: accuracy against cost, uniform against adaptive.

Four flows, each run at a ladder of particle sizes h = f h0 (h0 the case's own, f = 2, sqrt 2, 1, 1/sqrt 2, 1/2) in
five ways:
  - uniform: the case as it is (its particles, Δt = f Δt0);
  - size: an adaptive size field ("particles": "unstructured", "size_field": "adaptive": h at the surface, the walls
    and the structures, growing by a quarter of the distance up to 4 h), Δt = f Δt0;
  - flow: the adaptive size field with its flow indicator: particles straining faster than 2.5 sqrt(g H) / H (H the
    water's depth at the start) sized h too;
  - step: uniform particles, the adaptive step (Courant 0.5, at most 4 f Δt0);
  - both: the adaptive size and the adaptive step.
Each run's error is measured against the finest uniform run of its flow (the reference):
  - dam_break_tank (monolithic scheme, the defaults, 1 s): the front's RMS difference in x/L up to the wall impact
    (the chart's error) and the difference of the energy above the rest state at 0.25 s (over its start);
  - sloshing_forced (monolithic, slip walls as constraints, 3 s): the RMS difference of the two wall elevations over
    the linear peak;
  - flexible_tank (monolithic fluid, T10 plate, IQN-IMVJ, 1 s): the tip displacement's RMS difference over its peak;
  - elastic_gate_antoci (fractional step with the advected detection, which the adaptive size needs, for all its
    runs; 0.4 s): the tip displacement's RMS difference over its peak.
The calm wave: the remeshed standing wave of sloshing_free/case_advected.json (10 periods, h = 0.02 m), uniform (h and
1.5 h) and graded (gradation 0.25 and 0.1, max_size 4 h; gradation 0.25 with max_size 2 h): the wave's energy (kinetic +
potential above the flat surface of the same area) kept at the end, against the particle count.
The gate's step sequence: the elastic gate at h0/sqrt 2 under fixed steps from 1/2 to 2 times its own and under the
adaptive step with three settings, each against the finest uniform run.
Cost: the CPU time of the run (one thread) and its particle-steps (the particles summed over the steps, log.csv).
At equal error: for each adaptive run, the cost the uniform runs would need for its error (log-log interpolation
along the uniform runs' front), over its own cost.
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

sys.path.insert(0, os.path.join(common.CASES, "tools"))
from lagfsi_post import particle_steps  # noqa: E402

S = common.Study("adaptivity", __doc__.splitlines()[0])
R2 = math.sqrt(2.0)
ADAPTIVE_SIZE = {"bodies.0.particles": "unstructured", "bodies.0.size_field": "adaptive"}
# flow: case, h0, dt0, end time, ladder of f for the uniform runs (the last is the reference) and for the others,
# extra settings of every run, the probes the error is measured on.
FLOWS = {
    "dam_break_tank": dict(case="dam_break_tank/case.json", h0=0.0073, dt0=1e-3, end=1.0, depth=0.292,
                           uniform=[2, R2, 1, 1 / R2, 0.5], adaptive=[2, R2, 1, 1 / R2], extra={}),
    "sloshing_forced": dict(case="sloshing_forced/case.json", h0=0.02, dt0=2.5e-3, end=3.0, depth=0.5,
                            uniform=[2, R2, 1, 1 / R2, 0.5], adaptive=[2, R2, 1, 1 / R2], extra={}),
    "flexible_tank": dict(case="flexible_tank/case.json", h0=0.1 / 30, dt0=1e-3, end=1.0, depth=0.08,
                          uniform=[2, R2, 1, 1 / R2, 0.5], adaptive=[2, R2, 1, 1 / R2], extra={}),
    "elastic_gate_antoci": dict(case="elastic_gate_antoci/case.json", h0=0.0025, dt0=5e-4, end=0.4, depth=0.14,
                                uniform=[2, R2, 1, 1 / R2, 0.5], adaptive=[2, R2, 1, 1 / R2],
                                extra={"bodies.0.domain_detection": "advected"}),
}
if S.quick:  # one uniform and one adaptive run per flow, short: the smoke test checks that the tables are written
    for flow, end in (("dam_break_tank", 0.1), ("sloshing_forced", 0.3), ("flexible_tank", 0.05),
                      ("elastic_gate_antoci", 0.03)):
        FLOWS[flow].update(end=end, uniform=[2], adaptive=[2])
VARIANTS = ["uniform", "size", "flow", "step", "both"]
STRAIN_FACTOR = 2.5  # the flow indicator's threshold over sqrt(g H) / H


def settings(flow, variant, f):
    c = FLOWS[flow]
    s = dict(c["extra"])
    s.update({"analysis.end_time": c["end"], "analysis.dt": f * c["dt0"], "bodies.0.spacing": f * c["h0"]})
    if variant in ("size", "flow", "both"):
        s.update(ADAPTIVE_SIZE)
    if variant == "flow":
        H = c["depth"]
        s["bodies.0.size_field"] = {"type": "adaptive", "strain_rate": STRAIN_FACTOR * math.sqrt(9.81 * H) / H}
    if variant in ("step", "both"):
        s["analysis.time_step"] = {"type": "adaptive", "courant": 0.5, "max": 4 * f * c["dt0"]}
    return s


def rms_difference(p, q, column, t_max=math.inf):
    """RMS over p's samples (t <= t_max) of p[column] - q[column] (q interpolated at p's times)."""
    e = [(u - common.interp_nan(t, q["time"], q[column])) ** 2 for t, u in zip(p["time"], p[column]) if t <= t_max]
    e = [x for x in e if math.isfinite(x)]
    return math.sqrt(sum(e) / len(e)) if e else float("nan")


def errors(flow, p, ref):
    """The run's errors against the reference run's probes `ref` (the first is the chart's)."""
    if flow == "dam_break_tank":
        L = 0.146
        impact = next((t for t, x in zip(ref["time"], ref["front_x"]) if x >= 4 * L - 0.011), ref["time"][-1])
        front = rms_difference(p, ref, "front_x", impact) / L
        e = [ke + pe - 1000.0 * 9.81 * a * a / (2 * 4 * L)
             for ke, pe, a in zip(p["kinetic_energy"], p["potential_energy"], p["fluid_area"])]
        er = [ke + pe - 1000.0 * 9.81 * a * a / (2 * 4 * L)
              for ke, pe, a in zip(ref["kinetic_energy"], ref["potential_energy"], ref["fluid_area"])]
        at = lambda t, y, ts: y[min(range(len(ts)), key=lambda k: abs(ts[k] - t))]  # noqa: E731
        t_e = min(0.25, p["time"][-1])
        return {"error": front, "energy_error": abs(at(t_e, e, p["time"]) / e[0] - at(t_e, er, ref["time"]) / er[0])}
    if flow == "sloshing_forced":
        peak = max(abs(v - 0.5) for v in ref["eta_left"] + ref["eta_right"])
        return {"error": 0.5 * (rms_difference(p, ref, "eta_left") + rms_difference(p, ref, "eta_right")) / peak}
    peak = max(abs(v) for v in ref["tip_ux"])
    return {"error": rms_difference(p, ref, "tip_ux") / peak}


def equal_error_cost(err, front):
    """The cost the uniform runs' front [(cost, error), ...] needs for the error `err` (log-log interpolation between
    the two runs whose errors bracket it), None outside their range."""
    pts = sorted(front)
    for (c0, e0), (c1, e1) in zip(pts, pts[1:]):
        if min(e0, e1) <= err <= max(e0, e1) and e0 > 0 and e1 > 0 and e0 != e1:
            s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(c0) + s * (math.log(c1) - math.log(c0)))
    return None


rows = []
for flow, c in FLOWS.items():
    runs = {}
    for variant in VARIANTS:
        for f in (c["uniform"] if variant == "uniform" else c["adaptive"]):
            tag = "%s_%s_f%.3f" % (flow, variant, f)
            runs[(variant, f)] = S.run(c["case"], tag, settings(flow, variant, f), timeout=3600)
    ref = runs[("uniform", c["uniform"][-1])]
    ref_p = ref.probes() if ref.has_probes() else None
    flow_rows = []
    for (variant, f), r in runs.items():
        row = {"flow": flow, "variant": variant, "f": f, "h": f * c["h0"], "exit_code": r.rc,
               "cpu_s": r.cpu if r.cpu is not None else r.wall, "wall_s": r.wall}
        if r.has_probes() and ref_p is not None:
            p = r.probes()
            row["t_end"] = p["time"][-1]
            row["steps"] = len(r.log()["nodes"])
            row["particle_steps"] = particle_steps(r.out)
            row["particles_start"] = r.log()["nodes"][0]
            row.update(errors(flow, p, ref_p))
        flow_rows.append(row)
    # At equal error, against the uniform runs but the reference.
    ok = [x for x in flow_rows if x["variant"] == "uniform" and x["exit_code"] == 0 and "error" in x
          and x["f"] != c["uniform"][-1]]
    for row in flow_rows:
        if row["variant"] == "uniform" or row.get("exit_code") != 0 or "error" not in row:
            continue
        for cost in ("cpu_s", "particle_steps"):
            u = equal_error_cost(row["error"], [(x[cost], x["error"]) for x in ok])
            row["uniform_over_" + cost] = u / row[cost] if u else float("nan")
    rows.extend(flow_rows)

# The gate's step sequence: its tip under fixed steps of several sizes and under the adaptive step's settings.
gate = FLOWS["elastic_gate_antoci"]
fg = 1 / R2
dtg = fg * gate["dt0"]
SEQUENCES = [("fixed, Δt/2", {"analysis.dt": dtg / 2}), ("fixed, Δt", {}), ("fixed, 1.41 Δt", {"analysis.dt": R2 * dtg}),
             ("fixed, 2 Δt", {"analysis.dt": 2 * dtg}),
             ("adaptive, C 0.5, at most 4 Δt", {"analysis.time_step": {"type": "adaptive", "courant": 0.5, "max": 4 * dtg}}),
             ("adaptive, C 0.5, at most Δt", {"analysis.time_step": {"type": "adaptive", "courant": 0.5, "max": dtg}}),
             ("adaptive, C 0.3, at most 4 Δt", {"analysis.time_step": {"type": "adaptive", "courant": 0.3, "max": 4 * dtg}}),
             ("adaptive, C 0.5, at most 4 Δt, growth 1.02",
              {"analysis.time_step": {"type": "adaptive", "courant": 0.5, "max": 4 * dtg, "growth": 1.02}})]
# The same two adaptive runs from inputs that differ in the last digit: Δt and h written with 15 digits.
ROUNDED = {"analysis.dt": float("%.15g" % dtg), "bodies.0.spacing": float("%.15g" % (fg * gate["h0"]))}
SEQUENCES += [(name + ", Δt and h to 15 digits", dict(sets, **ROUNDED)) for name, sets in (SEQUENCES[4], SEQUENCES[7])]
if S.quick:
    SEQUENCES = SEQUENCES[1:2]
gate_ref_run = S.run(gate["case"], "elastic_gate_antoci_uniform_f%.3f" % gate["uniform"][-1],
                     settings("elastic_gate_antoci", "uniform", gate["uniform"][-1]), timeout=3600)
sequences = []
for name, sets in SEQUENCES:
    r = S.run(gate["case"], "gate_sequence_" + name.replace(" ", "_").replace(",", "").replace("/", "_"),
              dict(settings("elastic_gate_antoci", "uniform", fg), **sets), timeout=3600)
    row = {"sequence": name, "exit_code": r.rc, "cpu_s": r.cpu if r.cpu is not None else r.wall}
    if r.has_probes() and gate_ref_run.has_probes():
        log = r.log()
        row.update(steps=len(log["dt"]), dt_min=min(log["dt"]), dt_max=max(log["dt"]),
                   error=errors("elastic_gate_antoci", r.probes(), gate_ref_run.probes())["error"])
    sequences.append(row)
S.table("gate_step_sequence.csv", sequences, ["sequence", "exit_code", "steps", "dt_min", "dt_max", "cpu_s", "error"])

# The calm wave: what a coarse moving bulk costs a standing wave's energy.
T1 = 1.18182  # its linear period
CALM = [("uniform h", {}), ("uniform 1.5 h", {"bodies.0.spacing": 0.03}),
        ("graded, gradation 0.25", {"bodies.0.size_field": "adaptive"}),
        ("graded, gradation 0.1", {"bodies.0.size_field": {"type": "adaptive", "gradation": 0.1}}),
        ("graded, max_size 2 h", {"bodies.0.size_field": {"type": "adaptive", "max_size": 0.04}})]
if S.quick:
    CALM = CALM[::2][:2]
calm = []
for name, sets in CALM:
    r = S.run("sloshing_free/case_advected.json", "calm_wave_" + name.replace(" ", "_").replace(",", ""),
              dict(sets, **{"analysis.end_time": T1 if S.quick else 10 * T1}), timeout=3600)
    row = {"variant": name, "exit_code": r.rc, "cpu_s": r.cpu if r.cpu is not None else r.wall}
    if r.has_probes():
        p = r.probes()
        wave = [ke + pe - 1000.0 * 9.81 * a * a / 2.0
                for ke, pe, a in zip(p["kinetic_energy"], p["potential_energy"], p["fluid_area"])]
        row.update(particles=r.log()["nodes"][0], energy_kept=wave[-1] / wave[0],
                   area_drift=p["fluid_area"][-1] / p["fluid_area"][0] - 1)
    calm.append(row)
S.table("calm_wave.csv", calm, ["variant", "exit_code", "particles", "cpu_s", "energy_kept", "area_drift"])

COLS = ["flow", "variant", "f", "h", "exit_code", "t_end", "steps", "particles_start", "particle_steps", "cpu_s",
        "wall_s", "error", "energy_error", "uniform_over_cpu_s", "uniform_over_particle_steps"]
S.table("adaptivity_runs.csv", rows, COLS)

TITLES = {"dam_break_tank": "dam break: front RMS (x/L) vs finest uniform",
          "sloshing_forced": "forced sloshing: elevation RMS / peak vs finest",
          "flexible_tank": "flexible tank: tip RMS / peak vs finest",
          "elastic_gate_antoci": "elastic gate: tip RMS / peak vs finest"}
for cost, filename, label in (("cpu_s", "adaptivity_cpu.png", "CPU time [s] (one thread)"),
                              ("particle_steps", "adaptivity_particle_steps.png", "particle-steps")):
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for ax, flow in zip(axes.flat, FLOWS):
        for j, variant in enumerate(VARIANTS):
            pts = sorted((x[cost], x["error"], x["f"]) for x in rows if x["flow"] == flow and x["variant"] == variant
                         and x.get("exit_code") == 0 and x.get("error", 0) > 1e-12 and cost in x)  # not the reference
            if pts:
                ax.loglog([q[0] for q in pts], [q[1] for q in pts], "o-", color="C%d" % j, label=variant)
                for q in pts:
                    ax.annotate("%.2g" % q[2], (q[0], q[1]), fontsize=6, xytext=(2, 2), textcoords="offset points")
        ax.set_title(TITLES[flow], fontsize=9)
        ax.set_xlabel(label)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel("error against the finest uniform run")
    fig.suptitle("Adaptive size and step against uniform particles: error against cost (labels: h / h0)")
    S.figure(fig, filename)


def f(v, fmt):
    return fmt % v if isinstance(v, (int, float)) and math.isfinite(v) else "–"


def md_table():
    out = ["| flow | variant | h / h0 | particles at start | steps | particle-steps | CPU s | error | "
           "uniform's CPU / this at equal error | uniform's particle-steps / this |", "|---" * 10 + "|"]
    for r in rows:
        err = f(r.get("error"), "%.3g") + ("" if r["exit_code"] == 0 else " (**failed** at %s s)" % f(r.get("t_end"), "%.3f"))
        if "energy_error" in r:
            err += " (energy %s)" % f(r["energy_error"], "%.1e")
        out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["flow"], r["variant"], f(r["f"], "%.3g"), f(r.get("particles_start"), "%.0f"), f(r.get("steps"), "%.0f"),
            f(r.get("particle_steps"), "%.3g"), f(r["cpu_s"], "%.1f"), err, f(r.get("uniform_over_cpu_s"), "%.2f"),
            f(r.get("uniform_over_particle_steps"), "%.2f")))
    out += ["", "The calm wave (`sloshing_free/case_advected.json`, 10 periods):", "",
            "| variant | particles | CPU s | wave energy kept | area drift |", "|---|---|---|---|---|"]
    for r in calm:
        out.append("| %s | %s | %s | %s | %s |" % (r["variant"], f(r.get("particles"), "%.0f"), f(r["cpu_s"], "%.1f"),
                                                 f(r.get("energy_kept"), "%.3f"), f(r.get("area_drift"), "%.1e")))
    out += ["", "The gate's step sequence (`elastic_gate_antoci` at h0/√2, Δt = %.3g s; error as above):" % dtg, "",
            "| steps | count | smallest Δt | largest Δt | CPU s | error |", "|---|---|---|---|---|---|"]
    for r in sequences:
        out.append("| %s | %s | %s | %s | %s | %s |" % (r["sequence"], f(r.get("steps"), "%.0f"), f(r.get("dt_min"), "%.2g"),
                                                   f(r.get("dt_max"), "%.2g"), f(r["cpu_s"], "%.1f"), f(r.get("error"), "%.3g")))
    return "\n".join(out)


S.readme_table(md_table())
S.finish([("adaptivity_runs.csv", "error"), ("adaptivity_runs.csv", "cpu_s"), ("calm_wave.csv", "energy_kept")])
