"""Study 4: sensitivity of the dam break in a tank to the alpha-shape parameter.

cases/dam_break_tank (L/20, dt = 1 ms, 1 s) with bodies.0.alpha in {1.0, 1.1, 1.2, 1.3, 1.5, 2.0}, both fluid
schemes. Per run: fluid-area drift (end, largest), front RMS against Koshizuka & Oka (as the case's plot.py),
wall-impact time, and the number of detached fluid particles. No probe or log column gives detached
particles, so they are counted in the fluid .vtu snapshots (every 0.05 s): fluid particles (kind 0) that belong
to no element of the alpha-shape mesh (isolated drops, which move ballistically and carry no area).
Usage: /usr/bin/python3 run.py [--quick] [--exe PATH] [--out DIR] [--publish]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import common  # noqa: E402
from common import plt  # noqa: E402

S = common.Study("alpha_sensitivity", __doc__.splitlines()[0])
if S.quick:
    ALPHAS, SCHEMES, END = [1.0, 1.2, 2.0], ["fractional_step"], 0.35
else:
    ALPHAS, SCHEMES, END = [1.0, 1.1, 1.2, 1.3, 1.5, 2.0], ["monolithic_pspg", "fractional_step"], 1.0

rows, series = [], {}
for scheme in SCHEMES:
    for alpha in ALPHAS:
        r = S.run("dam_break_tank/case.json", "%s_alpha%.1f" % (scheme, alpha),
                  {"analysis.end_time": END, "bodies.0.alpha": alpha, "bodies.0.scheme.type": scheme,
                   "bodies.0.domain_detection": "alpha",
                   "output.every": 50}, timeout=900)
        row = {"scheme": scheme, "alpha": alpha, "exit_code": r.rc, "status": r.summary.get("status", "?"),
               "t_end": r.summary.get("time", float("nan")), "wall_time_s": r.solver_wall,
               "step_retries": r.summary.get("step_retries", 0)}
        if r.has_probes():
            row.update(common.dam_break_tank_errors(r))
            row["area_drift_end_pct"], row["area_drift_max_pct"] = common.area_drift(r)
            ts, det, nfl = [], [], []
            for t, path in common.pvd_files(r.out, "water.pvd"):
                v = common.read_vtu(path)
                ts.append(t)
                det.append(common.detached_fluid_particles(v))
                nfl.append(sum(1 for k in v["kind"] if k == 0))
            row["detached_end"], row["detached_max"] = det[-1], max(det)
            row["detached_mean"] = sum(det) / len(det)
            row["fluid_particles_end"] = nfl[-1]
            row["detached_end_pct"] = 100.0 * det[-1] / max(nfl[-1], 1)
            log = r.log()
            a0 = log["fluid_area"][0]
            series[(scheme, alpha)] = (log["time"], [100 * (a / a0 - 1) for a in log["fluid_area"]], ts, det)
        rows.append(row)

cols = ["scheme", "alpha", "exit_code", "status", "t_end", "wall_time_s", "step_retries", "area_drift_end_pct",
        "area_drift_max_pct", "front_rms_pysph", "front_rms_dsph", "impact_time", "detached_end", "detached_max",
        "detached_mean", "fluid_particles_end", "detached_end_pct"]
S.table("alpha_runs.csv", rows, cols)

fig, axes = plt.subplots(2, 3, figsize=(16, 8))
for k, scheme in enumerate(SCHEMES):
    sel = [r for r in rows if r["scheme"] == scheme and "front_rms_pysph" in r]
    a = [r["alpha"] for r in sel]
    c = "C%d" % k
    axes[0, 0].plot(a, [r["area_drift_end_pct"] for r in sel], "o-", color=c, label=scheme + " (end)")
    axes[0, 0].plot(a, [r["area_drift_max_pct"] for r in sel], "s--", color=c, mfc="none",
                    label=scheme + " (largest)")
    axes[0, 1].plot(a, [r["front_rms_pysph"] for r in sel], "o-", color=c, label=scheme + " (pysph)")
    axes[0, 1].plot(a, [r["front_rms_dsph"] for r in sel], "s--", color=c, mfc="none",
                    label=scheme + " (DualSPHysics)")
    axes[0, 2].plot(a, [r["detached_end"] for r in sel], "o-", color=c, label=scheme + " (end)")
    axes[0, 2].plot(a, [r["detached_max"] for r in sel], "s--", color=c, mfc="none", label=scheme + " (largest)")
for ax, yl in zip(axes[0], ["fluid area drift [%]", "front RMS in Z (up to the wall)",
                            "detached fluid particles"]):
    ax.set_xlabel("alpha")
    ax.set_ylabel(yl)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
for k, scheme in enumerate(SCHEMES[:2]):
    ax = axes[1, k]
    for j, alpha in enumerate(ALPHAS):
        if (scheme, alpha) in series:
            t, d, _, _ = series[(scheme, alpha)]
            ax.plot(t, d, color=plt.cm.viridis(j / max(len(ALPHAS) - 1, 1)), label="alpha %.1f" % alpha)
    ax.set_title(scheme)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("area drift [%]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
ax = axes[1, 2]
for k, scheme in enumerate(SCHEMES):
    for j, alpha in enumerate(ALPHAS):
        if (scheme, alpha) in series:
            _, _, ts, det = series[(scheme, alpha)]
            ax.plot(ts, det, ["-", "--"][k], color=plt.cm.viridis(j / max(len(ALPHAS) - 1, 1)),
                    label="%s %.1f" % (scheme[:4], alpha))
ax.set_xlabel("t [s]")
ax.set_ylabel("detached fluid particles")
ax.grid(alpha=0.3)
ax.legend(fontsize=6, ncol=2)
fig.suptitle("dam_break_tank, L/20, dt = 1 ms, %.2f s: alpha sensitivity" % END)
S.figure(fig, "alpha_sensitivity.png")

S.finish([("alpha_runs.csv", "area_drift_end_pct"), ("alpha_runs.csv", "front_rms_pysph"),
          ("alpha_runs.csv", "detached_max")])
