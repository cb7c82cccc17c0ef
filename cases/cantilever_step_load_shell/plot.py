"""Cantilever under a step load (Avancini 2018, sec. 5.5.1) with shell elements: the free end's deflection against the
Timoshenko static value and twice it, and against the T10 run of cantilever_step_load when its output folder
is given. Usage: /usr/bin/python3 cases/cantilever_step_load_shell/plot.py OUTDIR [T10_OUTDIR]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
from lagfsi_post import read_csv, out_dir_from_argv, save, shell_vs_continuum
from claims_record import record

out = out_dir_from_argv("out/cantilever_step_load_shell")
t10 = sys.argv[2] if len(sys.argv) > 2 else "out/cantilever_step_load"
ref = read_csv(os.path.join(os.path.dirname(__file__), "reference", "analytic.csv"))
static = ref["value"][ref["quantity"].index("tip_uy_static_timoshenko")]
p = read_csv(os.path.join(out, "probes.csv"))
peak = min(p["tip_uy_axis"])
# Energy balance (E_kin + E_strain - W_ext, probe energy_balance) relative to the largest total energy.
record("energy_balance", max(abs(b) for b in p["energy_balance"]) / max(abs(e) for e in p["energy_total"]))
fig, lines = shell_vs_continuum(out, t10, ["tip_uy_axis"], "", scale=1.0, unit="m")
lines.insert(0, "peak %.5f m = %.4f x the Timoshenko static deflection %.5f m" % (peak, peak / static, static))
ax = fig.axes[0]
ax.axhline(static, color="k", ls=":", label="static (Timoshenko)")
ax.axhline(2 * static, color="gray", ls=":", label="2 x static")
ax.legend(fontsize=8)
ax.set_title("cantilever step load, 6 cubic shell elements: " + lines[0], fontsize=9)
print("\n".join(lines))
save(fig, out)
