"""Column under self-weight (MPM): particles' vertical displacement and stress at the end of the run against
u = -(rho g / E_oed)(H z - z^2/2) and sigma = -rho g (H - z) (reference/mpm_selfweight_column_analytic.csv,
case cbgeo_hydrostatic_column). Reads OUTDIR/column_particles.csv.
Usage: /usr/bin/python3 cases/mpm_column_selfweight/plot.py OUTDIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save

out = out_dir_from_argv("out/mpm_column_selfweight")
c = read_csv(os.path.join(out, "column_particles.csv"))
rho, g, E, H = 1800.0, 9.81, 1.0e6, 0.1
Z = c["Y"]
u = [y - Y for y, Y in zip(c["y"], Z)]
ua = [-(rho * g / E) * (H * z - z * z / 2) for z in Z]
sa = [-rho * g * (H - z) for z in Z]
top = max(range(len(Z)), key=lambda i: Z[i])
s_err = max(abs(s - a) for s, a in zip(c["syy"], sa)) / (rho * g * H)
record("settlement", u[top])
record("settlement_analytic", ua[top])
record("stress_error", s_err)
lines = ["top particle settlement %.4e m (analytic %.4e m, %+.3f %%); largest stress error %.2f %% of rho g H" %
         (u[top], ua[top], 100 * (u[top] / ua[top] - 1), 100 * s_err)]
print("\n".join(lines))
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "mpm_selfweight_column_analytic.csv"))
rz = [z for k, z in zip(ref["case"], ref["z_m"]) if k == "cbgeo_hydrostatic_column"]
ru = [v for k, v in zip(ref["case"], ref["u_z_m"]) if k == "cbgeo_hydrostatic_column"]
rs = [v for k, v in zip(ref["case"], ref["sigma_v_Pa"]) if k == "cbgeo_hydrostatic_column"]
fig, axes = plt.subplots(1, 2, figsize=(10, 5), sharey=True)
axes[0].plot([1e6 * v for v in u], Z, "o", ms=3, label="MPM particles")
axes[0].plot([1e6 * v for v in ru], rz, "k-", lw=1, label="analytic")
axes[0].set_xlabel("u_y [um]")
axes[0].set_ylabel("z [m]")
axes[1].plot(c["syy"], Z, "o", ms=3, label="MPM particles")
axes[1].plot(rs, rz, "k-", lw=1, label="analytic")
axes[1].set_xlabel("sigma_yy [Pa]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("column under self-weight: " + lines[0], fontsize=8)
save(fig, out)
