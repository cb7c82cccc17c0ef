"""EFG L-panel, polynomial-basis study (thesis §5.3, Figs 5.9-5.11): the bilinear basis on Q4 cells against the
biquadratic basis on Q9 cells (Q9 coupling elements), rho = 2h and 3h, and the FEM Q9 reference.
Usage: /usr/bin/python3 cases/efg_L_panel/plot_basis.py LIN_2H LIN_3H QUAD_2H QUAD_3H [FEM_Q9]
(output directories of runs with the probes load and node_A_uy). Prints the peaks and the two comparisons of the
thesis — the spread of the limit loads from rho = 2h to 3h with each basis, and the effect of the basis against
that of rho — and draws basis.png into the first directory: FEM Q9 and the quadratic basis (Fig 5.9), linear
against quadratic at rho = 2h (Fig 5.10) and at 3h (Fig 5.11)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

if len(sys.argv) not in (5, 6):
    sys.exit(__doc__)
keys = ["lin_2h", "lin_3h", "quad_2h", "quad_3h", "fem_q9"]
labels = {"lin_2h": "EFG bilinear, ρ = 2h", "lin_3h": "EFG bilinear, ρ = 3h", "quad_2h": "EFG biquadratic, ρ = 2h",
          "quad_3h": "EFG biquadratic, ρ = 3h", "fem_q9": "FEM Q9, 6 × 6 Gauss"}
runs = {k: read_csv(os.path.join(o, "probes.csv")) for k, o in zip(keys, sys.argv[1:])}
peak = {}
for k, p in runs.items():
    i = max(range(len(p["load"])), key=lambda j: p["load"][j])
    peak[k] = p["load"][i]
    record("peak_%s" % k, peak[k])
    print("%-26s peak %.0f N at node_A_uy %.4f mm; last %.0f N at %.4f mm; initial slope %.1f N/mm"
          % (labels[k], peak[k], p["node_A_uy"][i], p["load"][-1], p["node_A_uy"][-1],
             p["load"][1] / p["node_A_uy"][1]))
spread_lin = peak["lin_3h"] / peak["lin_2h"] - 1
spread_quad = peak["quad_3h"] / peak["quad_2h"] - 1
basis = max(abs(peak["quad_2h"] / peak["lin_2h"] - 1), abs(peak["quad_3h"] / peak["lin_3h"] - 1))
print("spread of the peaks 2h -> 3h: bilinear %+.2f %%, biquadratic %+.2f %% (ratio %.3f)"
      % (100 * spread_lin, 100 * spread_quad, spread_quad / spread_lin))
print("basis effect (largest |quadratic / linear - 1| at 2h, 3h): %.2f %%; over the rho effect (bilinear): %.3f"
      % (100 * basis, basis / spread_lin))
record("spread_ratio", spread_quad / spread_lin)
record("basis_over_rho", basis / spread_lin)
if "fem_q9" in peak:
    print("FEM Q9 peak / EFG biquadratic rho = 2h peak: %.4f" % (peak["fem_q9"] / peak["quad_2h"]))
    record("fem_q9_over_quad_2h", peak["fem_q9"] / peak["quad_2h"])

panels = [("quadratic basis (Fig 5.9)", ["fem_q9", "quad_2h", "quad_3h"]),
          ("ρ = 2h (Fig 5.10)", ["lin_2h", "quad_2h"]), ("ρ = 3h (Fig 5.11)", ["lin_3h", "quad_3h"])]
fig, ax = plt.subplots(1, 3, figsize=(15, 4), sharey=True)
for a, (title, ks) in zip(ax, panels):
    for k in ks:
        if k in runs:
            a.plot(runs[k]["node_A_uy"], [v / 1e3 for v in runs[k]["load"]], "-", lw=1, label=labels[k])
    a.set_title(title)
    a.set_xlabel("node A vertical displacement (mm)")
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
ax[0].set_ylabel("load (kN)")
save(fig, sys.argv[1], "basis.png")
