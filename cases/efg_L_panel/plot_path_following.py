"""EFG L-panel, path-following study (thesis §5.4, Tables 5.1-5.2, Figs 5.12-5.17): the U form (the control acts on
displacements u = f(v)) against the V form (on the MLS parameters v) of displacement control at node B (CDD),
generalized displacement control (CDG) and cylindrical arc length (CAC).
Usage: /usr/bin/python3 cases/efg_L_panel/plot_path_following.py CDD_U CDD_V [CDG_U CDG_V [CAC_U CAC_V]]
(output directories of runs with the probes lambda, node_A_uy, node_A_vy, node_B_uy, node_B_vy). Prints the
tables (steps 1-4 and the last two), the linear-regime identities, and draws path_following_A.png (lambda against
u_A, the U and V forms of each method; Figs 5.12-5.13) and path_following_B.png (lambda against u_B and v_B for CDD
and CAC; Figs 5.14-5.17) into the first directory."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, save

if len(sys.argv) < 3 or len(sys.argv) % 2 == 0:
    sys.exit(__doc__)
names = ["CDD", "CDG", "CAC"]
runs = {}  # (method, form) -> columns
for k, o in enumerate(sys.argv[1:]):
    runs[(names[k // 2], "UV"[k % 2])] = read_csv(os.path.join(o, "probes.csv"))


def steps(p):
    """Rows of the committed steps 0..n (a step cut back by the driver adds rows at intermediate times)."""
    n = round(1 / min(t2 - t1 for t1, t2 in zip(p["time"], p["time"][1:])))
    rows = {}
    for i, t in enumerate(p["time"]):
        j = round(t * n)
        if abs(t * n - j) < 1e-6:
            rows[j] = i
    return rows


def row(p, i, cols):
    return "  ".join("%.10f" % p[c][i] for c in cols)


for (m, f), p in runs.items():
    rows = steps(p)
    last = max(rows)
    i = max(range(len(p["lambda"])), key=lambda k: p["lambda"][k])
    print("%s %s: %d steps; peak lambda %.4f (%.0f N) at u_A %.4f mm; last lambda %.4f at u_A %.4f mm, u_B %.4f mm"
          % (m, f, last, p["lambda"][i], p["load"][i], p["node_A_uy"][i], p["lambda"][rows[last]],
             p["node_A_uy"][rows[last]], p["node_B_uy"][rows[last]]))
    record("peak_lambda_%s_%s" % (m, f), p["lambda"][i])
    record("last_lambda_%s_%s" % (m, f), p["lambda"][rows[last]])
    print("   step  u_A_y  v_A_y  u_B_y  v_B_y  lambda")
    for j in [1, 2, 3, 4, last - 1, last]:
        print("   %4d  %s" % (j, row(p, rows[j], ["node_A_uy", "node_A_vy", "node_B_uy", "node_B_vy", "lambda"])))

# The linear-regime identities of displacement control at B (the digest's checks on Tables 5.1-5.2): step 1 of the
# V form imposes v_B = c, of the U form u_B = c; in the linear regime the response is proportional to lambda, so
# lambda(V) / lambda(U) = (c / v_B) / (c / u_B) = u_B / v_B, exactly.
pu, pv = runs[("CDD", "U")], runs[("CDD", "V")]
iu, iv = steps(pu)[1], steps(pv)[1]
ratio_lambda = pv["lambda"][iv] / pu["lambda"][iu]
ratio_uv = pv["node_B_uy"][iv] / pv["node_B_vy"][iv]
ratio_uv_u = pu["node_B_uy"][iu] / pu["node_B_vy"][iu]
print("step 1: lambda(V)/lambda(U) = %.10f; u_B/v_B = %.10f (V run), %.10f (U run); identity residual %.2e"
      % (ratio_lambda, ratio_uv, ratio_uv_u, ratio_lambda / ratio_uv - 1))
print("step 1: v_B/u_B = %.6f; initial slope lambda/u_A = %.4f per mm; u_B/u_A = %.5f; v_A/u_A = %.6f"
      % (1 / ratio_uv, pu["lambda"][iu] / pu["node_A_uy"][iu], pu["node_B_uy"][iu] / pu["node_A_uy"][iu],
         pu["node_A_vy"][iu] / pu["node_A_uy"][iu]))
record("identity_residual", abs(ratio_lambda / ratio_uv - 1))
record("lambda_ratio_VU_step1", ratio_lambda)
record("vB_over_uB", 1 / ratio_uv)
record("slope_lambda_per_uA", pu["lambda"][iu] / pu["node_A_uy"][iu])
record("uB_over_uA", pu["node_B_uy"][iu] / pu["node_A_uy"][iu])
for m in names:
    if (m, "V") in runs:  # peak of the V form over that of the U form
        a, b = runs[(m, "U")], runs[(m, "V")]
        r = max(b["lambda"]) / max(a["lambda"])
        print("%s: peak lambda V / U = %.6f" % (m, r))
        record("peak_ratio_VU_%s" % m, r)

out = sys.argv[1]
fig, ax = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
for (m, f), p in runs.items():
    ax[0 if f == "U" else 1].plot(p["node_A_uy"], p["lambda"], "-", lw=1, label=m)
for a, f in zip(ax, "UV"):
    a.set_title("%s form (control on %s)" % (f, "displacements u" if f == "U" else "parameters v"))
    a.set_xlabel("node A vertical displacement u_A (mm)")
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
ax[0].set_ylabel("load factor λ (λ = 1: 7 kN)")
save(fig, out, "path_following_A.png")

meths = [m for m in ("CDD", "CAC") if (m, "U") in runs]
fig, ax = plt.subplots(1, len(meths), figsize=(5.5 * len(meths), 4), sharey=True, squeeze=False)
for a, m in zip(ax[0], meths):
    for f, st in (("U", "-"), ("V", "--")):
        p = runs[(m, f)]
        a.plot(p["node_B_uy"], p["lambda"], st, lw=1, label="%s %s: u_B" % (m, f))
        a.plot(p["node_B_vy"], p["lambda"], st, lw=1, label="%s %s: v_B" % (m, f))
    a.set_xlabel("node B vertical displacement u_B / parameter v_B (mm)")
    a.set_title(m)
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
ax[0][0].set_ylabel("load factor λ")
save(fig, out, "path_following_B.png")
