"""Study: speed against accuracy on the Turek & Hron (2006) FSI2 and FSI3 benchmarks (PFEM-FEM, Dirichlet-Neumann).

cases/turek_hron_fsi2 (Re = 100, a flag ten times as dense as the water) and cases/turek_hron_fsi3 (Re = 200, a flag as
dense as the water), each at h = 0.02, 0.014 and 0.01 m (the fluid's spacing, the flag's mesh size and the coupling's
ghost spacing), with the time step scaled with h at the case's Courant number (FSI2: dt = h / 4, 2.5 ms at h = 0.01 m;
FSI3: dt = h / 10, 1 ms at h = 0.01 m), over the cases' run lengths (FSI2 12 s, FSI3 8 s). The case files are
written by the cases' own make_case.py (`case(h, dt, end_time, tag)`); the statistics are the cases' plot.py's
(cases/tools/turek_hron.py `fsi_oscillation`: the benchmark's mean and amplitude over the last period of the tip's
displacement, the forces' phase average; FSI2 over the last 4 s, FSI3 over the last 2 s), plus, for the tip's
u_y, the mean and the spread of the amplitude over every period of the window. Per run: the CPU time, the steps, the
retried steps, the coupling passes per step and the CPU time per step and per coupling pass; the errors against the
benchmark's values (the cases' reference/). Beside them, what other codes report for the same cases (published.csv,
each row with its source). Charts: each error against CPU time, one chart per case. Quick mode:
h = 0.02 m only, the start-up (FSI2 0.3 s, FSI3 0.15 s).
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish] [--no-nice]"""
import csv
import importlib.util
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import common  # noqa: E402
from common import plt  # noqa: E402
import turek_hron  # noqa: E402

S = common.Study("turek_hron_fsi", __doc__.splitlines()[0])


def load_make_case(name):
    """The make_case module of cases/<name> (from --cases)."""
    spec = importlib.util.spec_from_file_location(name, os.path.join(S.cases, name, "make_case.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# Per case: the benchmark's test, dt / h (the case's Courant number), the run length, the statistics' window and the
# forces' running mean (the cases' plot.py), the periodogram's band.
CASES = {
    "FSI2": {"dir": "turek_hron_fsi2", "dt_per_h": 0.25, "end": 12.0, "window": 4.0, "smooth": 0.025,
             "band": (0.5, 10.0)},
    "FSI3": {"dir": "turek_hron_fsi3", "dt_per_h": 0.1, "end": 8.0, "window": 2.0, "smooth": 0.01,
             "band": (0.5, 20.0)},
}
# The spacings h of each case. h = 0.007 m is left out: a step of FSI2 there costs about four times one at 0.01 m (a
# trial run's first 2 s), about an hour of CPU for 12 s of flow; FSI3's run at 0.007 m in cases/turek_hron_fsi3/README.md
# took 1553 s for 2.5 s of flow.
LEVELS = {"FSI2": [0.02, 0.014, 0.01], "FSI3": [0.02, 0.014, 0.01]}
if S.quick:
    LEVELS = {"FSI2": [0.02], "FSI3": [0.02]}
    CASES["FSI2"]["end"], CASES["FSI3"]["end"] = 0.3, 0.15
MEASURES = [  # (quantity, statistic, label in the table and the charts)
    ("uy_A", "amplitude", "u_y(A) amplitude"), ("uy_A", "frequency", "u_y(A) frequency"),
    ("ux_A", "amplitude", "u_x(A) amplitude"), ("drag", "mean", "drag mean"), ("drag", "amplitude", "drag amplitude"),
    ("lift", "amplitude", "lift amplitude")]


def case_file(test, h):
    """Writes the case of `test` at spacing h (the case's make_case.py) into the output folder; returns its path and
    dt."""
    spec = CASES[test]
    dt = round(spec["dt_per_h"] * h, 10)
    c = load_make_case(spec["dir"]).case(h, dt, spec["end"], "h = %g m, dt = %g s" % (h, dt))
    c["output"] = dict(c.get("output", {}), vtk=False)
    folder = os.path.join(S.out, "cases_" + ("quick" if S.quick else "full"))
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "%s_h%g.json" % (test.lower(), h))
    with open(path, "w") as f:
        json.dump(c, f, indent=1)
    return path, dt


def period_amplitudes(t, u, t0):
    """The amplitude (max - min)/2 of u over each period between the upward crossings of its mid-level (with the
    hysteresis of lagfsi_post.last_period_stats) after t0: [(start, end, amplitude)]."""
    k0 = next(k for k, tk in enumerate(t) if tk >= t0)
    tw, w = t[k0:], u[k0:]
    mid, band = 0.5 * (max(w) + min(w)), 0.1 * (max(w) - min(w))
    ups, armed = [], False
    for i in range(1, len(w)):
        if w[i] < mid - band:
            armed = True
        if armed and w[i - 1] < mid <= w[i]:
            ups.append(i)
            armed = False
    return [(tw[a], tw[b], 0.5 * (max(w[a:b + 1]) - min(w[a:b + 1]))) for a, b in zip(ups, ups[1:])]


def noise_std(t, v, width, t0):
    """The standard deviation, over t >= t0, of a force about its centred running mean over `width` s (the mean
    fsi_oscillation takes before its phase average): the step-to-step noise of the remeshing."""
    dt = t[1] - t[0]
    n = max(0, int(round(0.5 * width / dt)))
    d = [v[k] - sum(v[max(0, k - n):k + n + 1]) / len(v[max(0, k - n):k + n + 1]) for k in range(len(v)) if t[k] >= t0]
    m = sum(d) / len(d)
    return math.sqrt(sum((x - m) ** 2 for x in d) / len(d))


rows = []
for h in sorted({h for hs in LEVELS.values() for h in hs}, reverse=True):  # the coarsest runs first (the cheapest)
    for test, spec in CASES.items():
        if h not in LEVELS[test]:
            continue
        path, dt = case_file(test, h)
        tag = "%s_h%g" % (test.lower(), h)
        r = S.run(path, tag, timeout=3600)
        row = {"case": test, "h": h, "dt": dt, "end_time": spec["end"], "exit_code": r.rc,
               "status": r.summary.get("status", "?"), "cpu_s": r.cpu if r.cpu is not None else r.wall,
               "steps": r.summary.get("steps", 0), "step_retries": r.summary.get("step_retries", 0)}
        if r.has_probes():
            ref = {k: dict(zip(("mean", "amplitude", "frequency"), v))
                   for k, v in turek_hron.reference(os.path.join(S.cases, spec["dir"]), test).items()}
            v = turek_hron.fsi_oscillation(r.out, os.path.join(S.cases, spec["dir"]), test, spec["window"],
                                           spec["smooth"], band=spec["band"])
            p = r.probes()
            t_end = p["time"][-1]
            row["t_end"] = t_end
            for q, stat, _ in MEASURES:
                row["%s_%s" % (q, stat)] = v["%s_%s" % (q, stat)]
                row["%s_%s_error" % (q, stat)] = v["%s_%s" % (q, stat)] / ref[q][stat] - 1
            row["ux_A_frequency"] = v["ux_A_frequency"]
            row["drag_frequency"], row["lift_frequency"] = v["drag_frequency"], v["lift_frequency"]
            per = period_amplitudes(p["time"], p["tip_uy"], t_end - min(spec["window"], 0.5 * t_end))
            amps = [a for _, _, a in per]
            row["uy_A_periods"] = len(amps)
            row["uy_A_amplitude_per_period_mean"] = sum(amps) / len(amps) if amps else float("nan")
            row["uy_A_amplitude_per_period_min"] = min(amps) if amps else float("nan")
            row["uy_A_amplitude_per_period_max"] = max(amps) if amps else float("nan")
            row["uy_A_amplitude_per_period_mean_error"] = (row["uy_A_amplitude_per_period_mean"]
                                                           / ref["uy_A"]["amplitude"] - 1)
            t0 = t_end - min(spec["window"], 0.5 * t_end)
            for name, series in zip(("drag", "lift"), turek_hron.total_forces(p)):
                row["%s_noise_std" % name] = noise_std(p["time"], series, spec["smooth"], t0)
            row["passes_per_step"] = v["iterations"]
            row["passes_per_step_window"] = v["iterations_window"]
            row["passes_max"] = v["iterations_max"]
            passes = sum(x for x in p["fsi_iterations"] if x > 0)
            row["cpu_per_step_s"] = row["cpu_s"] / row["steps"] if row["steps"] else float("nan")
            row["cpu_per_pass_s"] = row["cpu_s"] / passes if passes else float("nan")
        rows.append(row)

cols = ["case", "h", "dt", "end_time", "exit_code", "status", "cpu_s", "steps", "step_retries", "t_end",
        "passes_per_step", "passes_per_step_window", "passes_max", "cpu_per_step_s", "cpu_per_pass_s"]
for q, stat, _ in MEASURES:
    cols += ["%s_%s" % (q, stat), "%s_%s_error" % (q, stat)]
cols += ["drag_noise_std", "lift_noise_std", "uy_A_periods", "uy_A_amplitude_per_period_mean", "uy_A_amplitude_per_period_mean_error",
         "uy_A_amplitude_per_period_min", "uy_A_amplitude_per_period_max", "ux_A_frequency", "drag_frequency",
         "lift_frequency"]
S.table("runs.csv", rows, cols)

# ---------------------------------------------------------------------------------------------- published
def published():
    """The rows of published.csv (what other codes report, with their sources), numbers as floats (None: not given),
    each with its errors against the case's reference (the benchmark's values in the cases' reference/)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "published.csv")
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    out = []
    for r in csv.DictReader(lines):
        for k, v in list(r.items()):
            if k not in ("case", "label", "method", "source", "time_note"):
                r[k] = float(v) if v.strip() else None
        ref = REFERENCE[r["case"]]
        for q, stat, _ in MEASURES:
            v = r.get("%s_%s" % (q, stat))
            r["%s_%s_error" % (q, stat)] = v / ref[q][stat] - 1 if v is not None else float("nan")
        out.append(r)
    return out


REFERENCE = {test: {k: dict(zip(("mean", "amplitude", "frequency"), v))
                    for k, v in turek_hron.reference(os.path.join(S.cases, spec["dir"]), test).items()}
             for test, spec in CASES.items()}
PUBLISHED = published()

# ------------------------------------------------------------------------------------------------- charts
COLOURS = {m[2]: "C%d" % k for k, m in enumerate(MEASURES)}
MARKERS = dict(zip([p["label"] for p in PUBLISHED], ["s", "D", "^", "v", "P", "X", "*"]))
FLOOR = 1e-3  # |error| below 0.1 % drawn here on the log scale
for test in CASES:
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(15, 7), gridspec_kw={"width_ratios": [3, 2]})
    mine = [r for r in rows if r["case"] == test and r["exit_code"] == 0 and "passes_per_step" in r]
    others = [p for p in PUBLISHED if p["case"] == test]
    for q, stat, label in MEASURES:
        key = "%s_%s_error" % (q, stat)
        pts = [(r["cpu_s"], max(abs(r[key]), FLOOR), r["h"]) for r in mine if math.isfinite(r.get(key, float("nan")))]
        if pts:
            ax.plot([c for c, _, _ in pts], [100 * e for _, e, _ in pts], "-o", color=COLOURS[label], label=label, lw=1)
            if label == MEASURES[0][2]:
                for c, e, h in pts:
                    ax.annotate("h = %g m" % h, (c, 100 * e), fontsize=7, xytext=(4, 6), textcoords="offset points")
        for p in others:  # published runs with a stated time, at that time
            if p["time_s"] and math.isfinite(p[key]):
                ax.plot([p["time_s"]], [100 * max(abs(p[key]), FLOOR)], MARKERS[p["label"]], color=COLOURS[label],
                        mfc="none", ms=8)
    for p in others:
        if p["time_s"]:
            ax.plot([], [], MARKERS[p["label"]], color="k", mfc="none", label="%s (%s)" % (p["label"], p["time_note"]))
    ax.axhline(5, color="k", ls="--", lw=0.8, label="5 % (tip amplitudes, frequencies)")
    ax.axhline(10, color="0.4", ls=":", lw=0.8, label="10 % (forces)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time [s] (lagfsi: one thread, %g s of flow; open markers: the source's time)" % CASES[test]["end"])
    ax.set_ylabel("|error| against Turek & Hron [%]")
    ax.set_title("%s: lagfsi's error against CPU time (h = %s m)" % (test, ", ".join("%g" % h for h in LEVELS[test])))
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    # right: every source's error per measure, lagfsi's runs beside them
    names = [m[2] for m in MEASURES]
    for k, (q, stat, label) in enumerate(MEASURES):
        key = "%s_%s_error" % (q, stat)
        for j, r in enumerate(mine):
            if math.isfinite(r.get(key, float("nan"))):
                bx.plot([k - 0.25 + 0.1 * j], [100 * max(abs(r[key]), FLOOR)], "o", color="C%d" % j, ms=6)
        for j, p in enumerate(others):
            if math.isfinite(p[key]):
                bx.plot([k + 0.1 + 0.08 * j], [100 * max(abs(p[key]), FLOOR)], MARKERS[p["label"]], color="k",
                        mfc="none", ms=7)
    for j, r in enumerate(mine):
        bx.plot([], [], "o", color="C%d" % j, label="lagfsi, h = %g m" % r["h"])
    for p in others:
        bx.plot([], [], MARKERS[p["label"]], color="k", mfc="none", label=p["label"])
    bx.set_xticks(range(len(names)))
    bx.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    bx.set_yscale("log")
    bx.set_ylabel("|error| against Turek & Hron [%]")
    bx.set_title("%s: lagfsi and published codes" % test)
    bx.grid(alpha=0.3, which="both", axis="y")
    bx.legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2)
    fig.tight_layout()
    S.figure(fig, "%s_error_vs_cpu.png" % test.lower())


# ------------------------------------------------------------------------------------------------- README
def pct(v):
    if not (isinstance(v, float) and math.isfinite(v)):
        return "–"
    return ("%+.2f %%" if abs(v) < 1e-3 else "%+.1f %%") % (100 * v)


def num(v, spec):
    return spec % v if isinstance(v, (int, float)) and math.isfinite(v) else "–"


cost = ["| case | h [m] | Δt [ms] | CPU [s] | steps (retried) | coupling passes / step (most) | CPU / step [s] | "
        "CPU / pass [s] | force noise: drag, lift [N/m] |", "|---|---|---|---|---|---|---|---|---|"]
errors = ["| case | h [m] | CPU [s] | " + " | ".join(m[2] for m in MEASURES)
          + " | u_y(A) amplitude per period: mean (min to max) |", "|---|---|---|" + "---|" * len(MEASURES) + "---|"]
for r in rows:
    if "passes_per_step" not in r:
        cost.append("| %s | %g | %g | %s | failed (%s) |" % (r["case"], r["h"], 1e3 * r["dt"], num(r["cpu_s"], "%.0f"),
                                                            r["status"]))
        continue
    amp_ref = REFERENCE[r["case"]]["uy_A"]["amplitude"]
    cost.append("| %s | %g | %g | %s | %d (%d) | %.2f (%d) | %.3f | %.4f | %.0f, %.0f |" % (
        r["case"], r["h"], 1e3 * r["dt"], num(r["cpu_s"], "%.0f"), r["steps"], r["step_retries"], r["passes_per_step"],
        r["passes_max"], r["cpu_per_step_s"], r["cpu_per_pass_s"], r["drag_noise_std"], r["lift_noise_std"]))
    errors.append("| %s | %g | %s | %s | %s (%s to %s; %d periods) |" % (
        r["case"], r["h"], num(r["cpu_s"], "%.0f"), " | ".join(pct(r["%s_%s_error" % (q, s_)]) for q, s_, _ in MEASURES),
        pct(r["uy_A_amplitude_per_period_mean_error"]), pct(r["uy_A_amplitude_per_period_min"] / amp_ref - 1),
        pct(r["uy_A_amplitude_per_period_max"] / amp_ref - 1), r["uy_A_periods"]))
lines = ["%d runs, %.0f s of CPU in all (the exe's commit in `results/meta.json`)." % (
    len(rows), sum(r["cpu_s"] for r in rows)), "", "Cost (force noise: the standard deviation of the drag and the lift about their centred running mean over the "
         "statistics' window, the step-to-step noise the phase average removes):", ""] + cost + [
    "", "Errors against the reference (last period and phase average, the cases' statistics; the last column over every "
    "period of the window):", ""] + errors
lines += ["", "What other codes report (`published.csv`, the sources there; errors against the same reference; "
          "– where the source gives no value):", "",
          "| case | code | method | " + " | ".join(m[2] for m in MEASURES) + " | time | passes / step |",
          "|---|---|---|" + "---|" * len(MEASURES) + "---|---|"]
for p in PUBLISHED:
    lines.append("| %s | %s | %s | %s | %s | %s |" % (
        p["case"], p["label"], p["method"], " | ".join(pct(p["%s_%s_error" % (q, s_)]) for q, s_, _ in MEASURES),
        p["time_note"] or "not stated", num(p["passes"], "about %.0f") if p["passes"] else "not stated"))
lines += ["", "Reference (the cases' `reference/`): " + "; ".join(
    "%s: %s" % (test, ", ".join("%s %.4g" % (label, REFERENCE[test][q][stat]) for q, stat, label in MEASURES))
    for test in CASES) + " (m, N/m, Hz)."]
S.readme_table("\n".join(lines))
S.finish([("runs.csv", "cpu_s"), ("runs.csv", "passes_per_step"), ("runs.csv", "uy_A_amplitude"),
          ("runs.csv", "drag_mean")])
