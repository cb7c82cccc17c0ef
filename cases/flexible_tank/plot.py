"""Flexible tank (Avancini 2018, sec. 7.3.1): tip displacement of the flexible wall and the pressure in the bottom-right
corner. No digitized reference exists for this case: the script prints the first peak, the first trough, the
mean deflection after the start-up (against the static beam-theory deflection under the initial hydrostatic
load) and the coupling statistics.
Usage: /usr/bin/python3 cases/flexible_tank/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, coupling_lines, peak

out = out_dir_from_argv("out/flexible_tank")
p = read_csv(os.path.join(out, "probes.csv"))
t, ux = p["time"], p["tip_ux"]

# Static deflection of a cantilever (EI per metre, plane strain, nu = 0) of length L = 0.1 under the triangular
# water load q(y) = rho g (H - y), H = 0.08: w(H) = q0 H^4/(30 EI), theta(H) = q0 H^3/(24 EI), tip = w + theta (L - H).
E, thick, L, H, rho, g = 1.0e6, 0.012, 0.1, 0.08, 1000.0, 9.81
EI = E * thick ** 3 / 12
q0 = rho * g * H
w_static = q0 * H ** 4 / (30 * EI) + q0 * H ** 3 / (24 * EI) * (L - H)

lines = []
tp, up = peak(t, ux, 0.3)
after = [(ti, ui) for ti, ui in zip(t, ux) if ti >= 0.2]
mean = sum(u for _, u in after) / len(after) if after else float("nan")
lines.append("tip_ux: first peak %.2f mm at %.3f s; mean over 0.2-%.1f s %.2f mm (static beam theory, water "
             "load only: %.2f mm)" % (1e3 * up, tp, t[-1], 1e3 * mean, 1e3 * w_static))
record("first_peak", up)
record("first_peak_time", tp)
record("mean_after_0.2", mean)
record("mean_over_beam_theory", mean / w_static)
record("peak_over_beam_theory", up / w_static)
trough = min(((ti, ui) for ti, ui in zip(t, ux) if tp < ti <= tp + 0.3), key=lambda x: x[1], default=None)
if trough:
    lines.append("first trough after the peak: %.2f mm at %.3f s" % (1e3 * trough[1], trough[0]))
lines += coupling_lines(out)
print("\n".join(lines))

fig, axes = plt.subplots(3, 1, figsize=(10, 8), sharex=True)
axes[0].plot(t, [1e3 * u for u in ux], label="tip u_x")
axes[0].axhline(1e3 * w_static, color="k", ls="--", lw=1, label="static beam theory (water load)")
axes[0].set_ylabel("u_x [mm]")
axes[1].plot(t, [1e3 * u for u in p["tip_uy"]], label="tip u_y")
axes[1].set_ylabel("u_y [mm]")
axes[2].plot(t, p["p_corner"], label="bottom-right corner")
axes[2].set_ylabel("pressure [Pa]")
axes[2].set_xlabel("t [s]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
axes[0].set_title("flexible tank: " + lines[0], fontsize=9)
save(fig, out)
