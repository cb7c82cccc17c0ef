"""Open-channel flow over an elastic flap: the water balance, the flap's steady deflection against Euler-Bernoulli
under the load the simulation puts on it, and the head over the flap against the sharp-crested weir equation.

Over the second half of the run (the statistically steady window [T/2, T]):
- balance: (A_end - A_0 - (entered - left)) / A_0 from summary.json (entered: the inflow's prescribed flux; left: the
  outlet's and the domain box's); balance_inflow: the same over the area that entered;
- tip_ux (m) the mean of the flap tip's horizontal displacement, tip_std its standard deviation, tip_halves the
  relative difference between the means of the window's two halves (steadiness);
- force (N/m) the mean interface force along x, force_pressure (N/m) the pressure difference across the flap
  integrated over its height from the probes 7.5 mm off each face (six 10 mm strips a side, each the mean pressure
  of the particles within 5 mm of it), force_ratio their ratio;
- tip_eb (m): Euler-Bernoulli's tip deflection of the flap (plane strain, E' = E / (1 - nu^2), I = t^3 / 12) under
  the load the simulation puts on it: hydrostatic to the upstream level on the upstream face, less a hydrostatic
  pool of depth `pool` (m) under the nappe on the downstream face, with the interface force as its total;
  tip_ratio = tip_ux / tip_eb; tip_eb_probes (m) Euler-Bernoulli's under the probes' pressure difference as it is
  (piecewise constant on the strips), tip_ratio_probes = tip_ux / tip_eb_probes;
- head (m) the mean water level at x = 0.2-0.4 m above the flap's tip, head_weir (m) the sharp-crested weir's head
  for the inflow's discharge (Rehbock: q = Cd 2/3 sqrt(2 g) H^1.5, Cd = 0.611 + 0.08 H / P, P the tip's height),
  head_ratio = head / head_weir; level (m) the upstream level, discharge_out the mean flow rate at x = 0.8 m over
  the inflow's;
- with a second OUTDIR (the run `solid`: case_solid.json, the flap alone under that load): tip_solid (m) and
  tip_ratio_solid = tip_ux / tip_solid.
Usage: /usr/bin/python3 cases/open_channel_flap/plot.py OUTDIR [SOLID_OUTDIR]"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from claims_record import record
from lagfsi_post import read_csv, out_dir_from_argv, save, water_balance

out = out_dir_from_argv("out/open_channel_flap")
tag = os.path.basename(os.path.normpath(out))
with open(os.path.join(out, "resolved_case.json")) as f:
    case = json.load(f)
water, flap = case["bodies"][0], case["bodies"][1]
mat = flap["material"]
E, NU = mat["young"], mat["poisson"]
T_FLAP, A = flap["geometry"]["size"][0], flap["geometry"]["size"][1]
EI = E / (1 - NU**2) * T_FLAP**3 / 12
inlet = water["boundaries"][0]
Q = inlet["velocity"][0] * (inlet["segment"][1][1] - inlet["segment"][0][1])
G, RHO = 9.81, water["density"]

p = read_csv(os.path.join(out, "probes.csv"))
with open(os.path.join(out, "summary.json")) as f:
    s = json.load(f)
t = p["time"]
T = t[-1]
win = [k for k, tk in enumerate(t) if tk >= 0.5 * T - 1e-9]
half = [k for k in win if t[k] < 0.75 * T]
half2 = [k for k in win if t[k] >= 0.75 * T]


def mean(col, ks=win):
    v = [p[col][k] for k in ks if not math.isnan(p[col][k])]
    return sum(v) / len(v)


fa = s["bodies"][0]["fluid_area"]
a0, a1, entered, left = fa["initial"], fa["final"], fa["entered_domain"], fa["left_domain"]
balance = (a1 - a0 - (entered - left)) / a0
balance_inflow = water_balance(out)  # the same over the inflow
tip = mean("tip_ux")
tip_std = math.sqrt(sum((p["tip_ux"][k] - tip) ** 2 for k in win) / len(win))
tip_halves = (mean("tip_ux", half2) - mean("tip_ux", half)) / tip
force = mean("force_x")
ys = [0.005 + 0.01 * k for k in range(6)]
dp = [mean("p_up_%d" % k) - mean("p_dn_%d" % k) for k in range(6)]
force_p = sum(d * 0.01 for d in dp)
crest = A + mean("tip_uy")
level = sum(mean("eta_%03d" % x) for x in (20, 30, 40)) / 3
# The load's shape: hydrostatic on the upstream face (the approach flow's velocity head is under 1 mm) to the
# upstream level, less a hydrostatic pool of depth d under the nappe on the downstream face, d such that the total
# is the interface force. A cantilever's tip deflection under w dy at height y: w dy y^2 (3 a - y) / (6 EI).
up = RHO * G * (level * A - A * A / 2)
pool = math.sqrt(max(0.0, 2 * (up - force) / (RHO * G)))


def tip_under(w, n=600):
    return sum(w((j + 0.5) * A / n) * (A / n) * y * y * (3 * A - y) / (6 * EI)
               for j in range(n) for y in [(j + 0.5) * A / n])


def load(y):
    return RHO * G * ((level - y) - max(0.0, pool - y))


tip_eb = tip_under(load)
tip_eb_probes = tip_under(lambda y: dp[min(5, int(y / 0.01))])
crest = A + mean("tip_uy")
level = sum(mean("eta_%03d" % x) for x in (20, 30, 40)) / 3
head = level - crest
hw = 0.03
for _ in range(50):
    hw = (Q / ((0.611 + 0.08 * hw / crest) * 2 / 3 * math.sqrt(2 * G))) ** (2 / 3)
record("balance", balance)
record("balance_inflow", balance_inflow)
record("tip_ux", tip)
record("tip_std", tip_std)
record("tip_halves", tip_halves)
record("force", force)
record("force_pressure", force_p)
record("force_ratio", force_p / force)
record("pool", pool)
record("tip_eb", tip_eb)
record("tip_ratio", tip / tip_eb)
record("tip_eb_probes", tip_eb_probes)
record("tip_ratio_probes", tip / tip_eb_probes)
record("level", level)
record("head", head)
record("head_weir", hw)
record("head_ratio", head / hw)
record("discharge_out", mean("q_080") / Q)
if len(sys.argv) > 2:
    tip_solid = read_csv(os.path.join(sys.argv[2], "probes.csv"))["tip_ux"][-1]
    record("tip_solid", tip_solid)
    record("tip_ratio_solid", tip / tip_solid)
    print("  flap alone under that load (case_solid.json): tip %.3f mm, FSI / solid %.3f" % (1e3 * tip_solid,
                                                                                           tip / tip_solid))
print("%s: balance %.2e of A0 (%.2e of the inflow)" % (tag, balance, balance_inflow))
print("  tip %.3f mm (std %.3f mm, halves %+.2f %%), force %.2f N/m (pressure probes %.2f, ratio %.3f); "
      "Euler-Bernoulli %.3f mm (ratio %.3f; under the probes' load %.3f mm, ratio %.3f)"
      % (1e3 * tip, 1e3 * tip_std, 100 * tip_halves, force, force_p, force_p / force, 1e3 * tip_eb, tip / tip_eb,
         1e3 * tip_eb_probes, tip / tip_eb_probes))
print("  level %.4f m, crest %.4f m, head %.4f m, weir %.4f m (ratio %.3f); outflow %.3f of q"
      % (level, crest, head, hw, head / hw, mean("q_080") / Q))

fig, axes = plt.subplots(1, 3, figsize=(15, 3.8))
axes[0].plot(t, [1e3 * u for u in p["tip_ux"]], lw=0.8, label="lagfsi tip u_x")
axes[0].axhline(1e3 * tip_eb, color="k", ls="--", label="Euler-Bernoulli, measured load")
axes[0].axvline(0.5 * T, color="0.6", lw=0.8)
axes[0].set_xlabel("t [s]")
axes[0].set_ylabel("tip u_x [mm]")
for x in (10, 20, 30, 40, 70, 85):
    axes[1].plot(t, p["eta_%03d" % x], lw=0.7, label="x = %.2f m" % (x / 100))
axes[1].axhline(crest + hw, color="k", ls="--", label="crest + weir head")
axes[1].set_xlabel("t [s]")
axes[1].set_ylabel("water level [m]")
yy = [A * j / 60 for j in range(61)]
axes[2].plot([RHO * G * (level - y) for y in yy], yy, "k-", lw=0.8, label="hydrostatic to the upstream level")
axes[2].plot([RHO * G * max(0.0, pool - y) for y in yy], yy, "k--", lw=0.8, label="hydrostatic pool under the nappe")
axes[2].plot([mean("p_up_%d" % k) for k in range(6)], ys, "o", label="probes 7.5 mm upstream of the flap")
axes[2].plot([mean("p_dn_%d" % k) for k in range(6)], ys, "s", label="probes 7.5 mm downstream")
axes[2].set_xlabel("mean pressure [Pa]")
axes[2].set_ylabel("y [m]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("open_channel_flap (%s)" % tag)
save(fig, out, "comparison_%s.png" % tag)
