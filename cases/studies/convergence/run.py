"""Study 2: observed orders of convergence of the solid, the fluid and the coupled solver.

- solid, cases/turek_csm3 (3 s instead of 10 s): tip u_y amplitude (Turek & Hron convention, the last full
  period) and frequency, against the mesh size (T10 elements, dt = 5 ms) and against dt (mesh size 0.01);
- fluid, cases/sloshing_free regenerated at each particle spacing (as its make_case.py; 3 periods instead of 5,
  dt = T1/200 instead of T1/100 so that the time error stays below the space error): period against the
  linear theory T1 = 1.18182 s;
- fluid, cases/hydrostatic (0.2 s instead of 1 s): largest error of the bottom pressure against rho g H, both
  schemes (fractional step at dt = 0.5 ms, as its README);
- FSI, cases/flexible_tank (0.25 s instead of 1 s, fractional-step fluid): the first peak of the tip
  displacement against h (fluid spacing and plate mesh refined together: the interface is matching, one ghost
  per plate node) and against dt.
Where no exact value exists (CSM3 in dt and h: the benchmark value is itself a discrete one; the flexible
tank) the finest run is the reference, and the observed order of the three finest runs is given by
Richardson's p = log(|q3 - q2| / |q2 - q1|) / log(r). Usage: /usr/bin/python3 run.py [--quick] [--exe PATH]
[--out DIR] [--publish]"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt, read_csv  # noqa: E402

S = common.Study("convergence", __doc__.splitlines()[0])
Q = S.quick
NOVTK = {"output.vtk": False}
rows = []


def add(study, param, value, run, **q):
    row = {"study": study, "parameter": param, "value": value, "exit_code": run.rc, "wall_time_s": run.solver_wall}
    row.update(q)
    rows.append(row)
    return row


# ------------------------------------------------------------------------------------------------- CSM3
ref = read_csv(os.path.join(common.CASES, "turek_csm3", "reference", "turek_hron_2006_reference_values.csv"))
TH = {qq: (m, a, f) for c, qq, m, a, f in zip(ref["case"], ref["quantity"], ref["mean"], ref["amplitude"],
                                               ref["frequency_Hz"]) if c == "CSM3"}
csm3_end = 2.5 if Q else 3.0
sizes = [0.04, 0.02] if Q else [0.04, 0.02, 0.01, 0.005]
dt_size = 0.02 if Q else 0.01
dts = [0.02, 0.01] if Q else [0.04, 0.02, 0.01, 0.005, 0.0025]


def csm3(size, dt):
    r = S.run("turek_csm3/case.json", "csm3_size%g_dt%g" % (size, dt),
              dict(NOVTK, **{"analysis.end_time": csm3_end, "analysis.dt": dt, "bodies.0.mesh.size": size}),
              timeout=900)
    q = {}
    if r.ok:
        p = r.probes()
        s = common.lagfsi_post.last_period_stats(p["time"], p["tip_uy"])
        if s:
            q = {"uy_amplitude": s["amplitude"], "uy_mean": s["mean"], "frequency": s["frequency"]}
    return r, q


for size in sizes:
    r, q = csm3(size, 0.005)
    add("csm3_mesh", "h", size, r, dofs=2 * r.summary.get("bodies", [{}])[0].get("nodes", 0), **q)
for dt in dts:
    r, q = csm3(dt_size, dt)
    add("csm3_dt", "dt", dt, r, **q)

# --------------------------------------------------------------------------------------- sloshing_free
Ls, d, g = 1.0, 0.5, 9.81
T1 = 2 * math.pi / math.sqrt(g * math.pi / Ls * math.tanh(math.pi / Ls * d))


def sloshing_case(h):
    """The case of cases/sloshing_free/make_case.py at spacing h, 3 periods, dt = T1/200."""
    a = 0.01 * d
    n = int(round(Ls / h))
    top = [[round(Ls * i / n, 10), round(d + a * math.cos(math.pi * i / n), 10)] for i in range(n, -1, -1)]
    return {
        "name": "sloshing_free_h%g" % h,
        "analysis": {"type": "dynamic", "dt": round(T1 / 200, 7), "end_time": round(3 * T1, 4),
                     "newton": {"max_iterations": 15}},
        "gravity": [0.0, -g],
        "bodies": [{
            "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": h,
            "remesh": False, "particles": "unstructured",
            "regions": [{"type": "polygon", "points": [[0.0, 0.0], [Ls, 0.0]] + top}],
            "walls": [{"name": "tank", "points": [[0, 2 * d], [0, 0], [Ls, 0], [Ls, 2 * d]], "slip": True}],
            "initial_pressure": {"type": "hydrostatic", "level": d},
            "scheme": {"volume_correction": "none", "free_surface_pressure": "natural"}}],
        "probes": [{"name": "eta_left", "type": "elevation", "body": "water", "x": 0.0, "band": 0.5 * h},
                   {"name": "fluid_area", "type": "fluid_area", "body": "water"}],
        "output": {"every": 100, "vtk": False}}


slosh_h = [0.08, 0.06] if Q else [0.08, 0.06, 0.04, 0.03, 0.02, 0.015]
os.makedirs(os.path.join(S.runs_dir, "cases"), exist_ok=True)
for h in slosh_h:
    path = os.path.join(S.runs_dir, "cases", "sloshing_free_h%g.json" % h)
    with open(path, "w") as f:
        json.dump(sloshing_case(h), f, indent=1)
    r = S.run(path, "sloshing_h%g" % h, timeout=900)
    q = {}
    if r.ok:
        p = r.probes()
        s = common.lagfsi_post.last_period_stats(p["time"], p["eta_left"])
        if s:
            q = {"period": 1 / s["frequency"], "period_error_rel": 1 / s["frequency"] / T1 - 1}
    add("sloshing_h", "h", h, r, particles=r.summary.get("bodies", [{}])[0].get("nodes", 0), **q)

# ----------------------------------------------------------------------------------------- hydrostatic
hydro_h = [0.02, 0.01] if Q else [0.02, 0.01, 0.005]
for scheme, dt in (("monolithic_pspg", 2e-3), ("fractional_step", 5e-4)):
    for h in hydro_h:
        r = S.run("hydrostatic/case.json", "hydrostatic_%s_h%g" % (scheme, h),
                  dict(NOVTK, **{"analysis.end_time": 0.2, "analysis.dt": dt, "bodies.0.spacing": h,
                                 "bodies.0.scheme.type": scheme, "bodies.0.domain_detection": "alpha"}), timeout=900)
        q = {}
        if r.ok:
            p = r.probes()
            pref = 1000 * 9.81 * 0.2
            q = {"p_bottom_error_rel": max(abs(x / pref - 1) for x in p["p_bottom"][1:])}
        add("hydrostatic_" + scheme, "h", h, r, **q)

# ---------------------------------------------------------------------------------------- flexible tank
H0 = 0.1 / 30  # fluid spacing = plate node spacing with [1, 10] T10 cells
flex_div = [5, 10] if Q else [5, 10, 20, 40]
flex_dt = [2e-3, 1e-3] if Q else [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]
flex_end = 0.2 if Q else 0.25


def flexible(div, dt, scheme="fractional_step"):
    h = 0.1 / (3 * div)
    tag = "flexible_div%d_dt%g" % (div, dt) + ("" if scheme == "fractional_step" else "_" + scheme)
    r = S.run("flexible_tank/case.json", tag,
              dict(NOVTK, **{"analysis.end_time": flex_end, "analysis.dt": dt, "bodies.0.spacing": h,
                             "bodies.1.mesh.divisions": [1, div], "bodies.0.scheme.type": scheme,
                             "bodies.0.domain_detection": "alpha"}),
              timeout=900)
    q = {}
    if r.ok:
        p = r.probes()
        tp, up = common.lagfsi_post.peak(p["time"], p["tip_ux"])
        q = {"tip_peak": up, "tip_peak_time": tp}
    return r, q, h


for div in flex_div:
    r, q, h = flexible(div, 1e-3)
    add("flexible_h", "h", h, r, **q)
for dt in flex_dt:
    r, q, h = flexible(10, dt)
    add("flexible_dt", "dt", dt, r, **q)
# The same dt series with the monolithic fluid (the case's scheme): which scheme sets the order in time.
for dt in ([] if Q else [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]):
    r, q, h = flexible(10, dt, "monolithic_pspg")
    add("flexible_dt_monolithic", "dt", dt, r, **q)

cols = ["study", "parameter", "value", "exit_code", "wall_time_s", "dofs", "particles", "uy_amplitude", "uy_mean",
        "frequency", "period", "period_error_rel", "p_bottom_error_rel", "tip_peak", "tip_peak_time"]
S.table("runs.csv", rows, cols)

# ------------------------------------------------------------------------------------------- orders
orders = []


def series(study, key):
    sel = sorted([r for r in rows if r["study"] == study and math.isfinite(r.get(key, float("nan")))],
                 key=lambda r: r["value"])
    return [r["value"] for r in sel], [r[key] for r in sel]


def analyse(study, key, label, exact=None, exact_label=""):
    """Errors against the finest run (and against `exact`); fitted slope; Richardson order of the 3 finest."""
    x, y = series(study, key)
    out = {"study": study, "quantity": key, "label": label, "n_runs": len(x)}
    if len(x) < 2:
        return out, x, y
    e_f = [abs(v - y[0]) for v in y[1:]]
    out["slope_vs_finest"], _ = common.fit_slope(x[1:], e_f)
    if len(x) >= 3:
        r1, r2 = x[1] / x[0], x[2] / x[1]
        d1, d2 = y[1] - y[0], y[2] - y[1]
        if d1 != 0 and d2 != 0 and abs(r1 - r2) < 1e-6 * r1:
            out["richardson_order"] = math.log(abs(d2 / d1)) / math.log(r1)
            out["richardson_sign_change"] = d1 * d2 < 0
            p = out["richardson_order"]
            out["richardson_extrapolated"] = y[0] - d1 / (r1 ** p - 1)
    if exact is not None:
        e_x = [abs(v - exact) for v in y]
        out["slope_vs_exact"], _ = common.fit_slope(x, e_x)
        if len(x) >= 4 and min(e_x) > 0:
            # e = e0 + C x^p: a floor e0 (another error source: dt, nonlinearity) fitted by a scan
            best = None
            for k in range(100):
                e0 = min(e_x) * k / 100
                pp, cc = common.fit_slope(x, [v - e0 for v in e_x])
                res = sum((math.log(v - e0) - (pp * math.log(xx) + cc)) ** 2 for xx, v in zip(x, e_x))
                if best is None or res < best[0]:
                    best = (res, e0, pp)
            out["slope_with_floor"], out["floor"] = best[2], best[1]
        out["exact"] = exact
        out["exact_source"] = exact_label
        out["error_finest_vs_exact_rel"] = (y[0] - exact) / abs(exact) if exact else y[0]
    out["finest"] = x[0]
    out["value_finest"] = y[0]
    return out, x, y


specs = [("csm3_mesh", "uy_amplitude", "CSM3 tip u_y amplitude vs mesh size", TH["uy_A"][1], "Turek & Hron"),
         ("csm3_mesh", "frequency", "CSM3 frequency vs mesh size", TH["uy_A"][2], "Turek & Hron"),
         ("csm3_dt", "uy_amplitude", "CSM3 tip u_y amplitude vs dt", None, ""),
         ("csm3_dt", "frequency", "CSM3 frequency vs dt", None, ""),
         ("sloshing_h", "period", "sloshing period vs h", T1, "linear theory"),
         ("hydrostatic_fractional_step", "p_bottom_error_rel", "hydrostatic p error (fractional step) vs h", 0.0,
          "rho g H"),
         ("hydrostatic_monolithic_pspg", "p_bottom_error_rel", "hydrostatic p error (monolithic) vs h", 0.0,
          "rho g H"),
         ("flexible_h", "tip_peak", "flexible tank tip peak vs h", None, ""),
         ("flexible_dt", "tip_peak", "flexible tank tip peak vs dt", None, ""),
         ("flexible_dt_monolithic", "tip_peak", "flexible tank tip peak vs dt, monolithic fluid", None, "")]
data = {}
for study, key, label, exact, src in specs:
    o, x, y = analyse(study, key, label, exact, src)
    orders.append(o)
    data[(study, key)] = (x, y, o)
S.table("orders.csv", orders, ["study", "quantity", "label", "n_runs", "finest", "value_finest", "slope_vs_finest",
                                "richardson_order", "richardson_sign_change", "richardson_extrapolated",
                                "exact", "exact_source", "slope_vs_exact", "slope_with_floor", "floor",
                                "error_finest_vs_exact_rel"])

# --------------------------------------------------------------------------------------------- chart
fig, axes = plt.subplots(2, 3, figsize=(17, 9))
panels = [(axes[0, 0], [("csm3_mesh", "uy_amplitude"), ("csm3_mesh", "frequency")], "mesh size h [m]",
           "CSM3 (dt = 5 ms)"),
          (axes[0, 1], [("csm3_dt", "uy_amplitude"), ("csm3_dt", "frequency")], "dt [s]", "CSM3 (h = %g)" % dt_size),
          (axes[0, 2], [("sloshing_h", "period")], "particle spacing h [m]", "sloshing_free (dt = T1/200)"),
          (axes[1, 0], [("hydrostatic_fractional_step", "p_bottom_error_rel"),
                        ("hydrostatic_monolithic_pspg", "p_bottom_error_rel")], "h [m]", "hydrostatic (0.2 s)"),
          (axes[1, 1], [("flexible_h", "tip_peak")], "fluid spacing h = plate node spacing [m]",
           "flexible_tank (dt = 1 ms)"),
          (axes[1, 2], [("flexible_dt", "tip_peak"), ("flexible_dt_monolithic", "tip_peak")], "dt [s]",
           "flexible_tank (h = 3.33 mm); C0 fractional step, C1 monolithic")]
for ax, keys, xlabel, title in panels:
    for k, key in enumerate(keys):
        x, y, o = data[key]
        if len(x) < 2:
            continue
        c = "C%d" % k
        if "exact" in o and key[1] != "p_bottom_error_rel":
            e = [abs(v - o["exact"]) / abs(o["exact"]) for v in y]
            ax.plot(x, e, "o-", color=c, label="%s vs %s (slope %.2f%s)" % (
                key[1], o["exact_source"], o.get("slope_vs_exact", float("nan")),
                "; %.2f above a floor %.1e" % (o["slope_with_floor"], o["floor"] / abs(o["exact"]))
                if "slope_with_floor" in o else ""))
        if key[1] == "p_bottom_error_rel":
            e = [max(v, 1e-16) for v in y]
            ax.plot(x, e, "o-", color=c, label="%s (slope %.2f)%s" % (
                key[0].replace("hydrostatic_", ""), o.get("slope_vs_exact", float("nan")),
                "; exactly rho g H (plotted at 1e-16)" if max(y) == 0 else ""))
            continue
        ef = [abs(v - y[0]) / abs(y[0]) for v in y[1:]]
        if any(v > 0 for v in ef):
            ax.plot(x[1:], [max(v, 1e-16) for v in ef], "s--", color=c, mfc="none",
                    label="%s vs finest (slope %.2f; Richardson p %s)" % (
                        key[1], o.get("slope_vs_finest", float("nan")),
                        "%.2f" % o["richardson_order"] if "richardson_order" in o else "-"))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative error")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6)
S.figure(fig, "convergence.png")

S.finish([("runs.csv", "wall_time_s"), ("runs.csv", "exit_code")],
         ["run %s %s = %g: exit code %d" % (r["study"], r["parameter"], r["value"], r["exit_code"])
          for r in rows if r["exit_code"] != 0 and S.quick])
