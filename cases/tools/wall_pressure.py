"""The wall-pressure measures of a dam break against a wall with pressure sensors (Zhou, De Kat & Buchner 1999;
Buchner 2002; Marrone et al. 2011), shared by cases/dam_break_pressure/plot.py and cases/studies/wall_pressure:
pressures p* = p / (rho g H) against t* = t sqrt(g / H); the impact time at P1 (the last time p* < 0.05 before it
first exceeds 0.3), the quasi-static plateau (the mean of p* over 3.5 < t* < 5), the pressure impulse of the first
0.1 s after the impact, the time the run-up wets P2 (p* > 0.05), the run-up's highest point and the largest share of
the water above 2 H; and the references (reference/ of the case, citations in the files' headers)."""
import math
import os

from lagfsi_post import read_csv

H, G, RHO = 0.6, 9.81, 1000.0
T_SCALE, P_SCALE = math.sqrt(G / H), RHO * G * H
IMPULSE_WINDOW = 0.1 * T_SCALE  # 0.1 s in t*
REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "dam_break_pressure", "reference")


def onset(t, p):
    """The last time p < 0.05 before p first exceeds 0.3 (NaN when it never does)."""
    k = next((i for i, v in enumerate(p) if v > 0.3), None)
    below = [i for i in range(k or 0) if p[i] < 0.05]
    return t[max(below)] if k is not None and below else float("nan")


def impulse(t, p, t0, width):
    """Trapezoidal integral of p over [t0, t0 + width] (linear interpolation at the ends)."""
    total = 0.0
    for i in range(len(t) - 1):
        lo, hi = max(t[i], t0), min(t[i + 1], t0 + width)
        if hi > lo:
            at = lambda x: p[i] + (p[i + 1] - p[i]) * (x - t[i]) / (t[i + 1] - t[i])
            total += 0.5 * (at(lo) + at(hi)) * (hi - lo)
    return total


def plateau(t, p):
    """The mean of p over 3.5 < t < 5 (NaN when the record ends before)."""
    vals = [v for x, v in zip(t, p) if 3.5 < x < 5.0]
    return sum(vals) / len(vals) if vals else float("nan")


def wets(t, p):
    """The first time p exceeds 0.05 (NaN when it never does)."""
    return next((x for x, v in zip(t, p) if v > 0.05), float("nan"))


def references():
    """The experiment at P1, the delta-SPH H/dx = 320 at P1, and P2's table (experiment and delta-SPH)."""
    return (read_csv(os.path.join(REFERENCE, "buchner2002_p1.csv")),
            read_csv(os.path.join(REFERENCE, "marrone2011_p1.csv")),
            read_csv(os.path.join(REFERENCE, "marrone2011_p2.csv")))


def measures(probes):
    """A run's measures from its probes.csv columns (time, p1, p2, runup, above_2H; p1_load when present): t*, P1
    and P2 in p*, and the impact, plateau, impulse, P2 wetting time, highest run-up and largest share above 2 H (and
    P1's impact, plateau and impulse read from the wall's load)."""
    t = [x * T_SCALE for x in probes["time"]]
    p2 = [v / P_SCALE for v in probes["p2"]]
    runup = [v for v in probes["runup"] if not math.isnan(v)]
    m = {"t": t, "p2": p2, "p2_wets": wets(t, p2), "runup_max": max(runup) if runup else float("nan"),
         "above_2H_max": max(probes["above_2H"])}
    # P1 from the particles' pressures, and from the wall's load over the sensor's face ("method": "load").
    for column, suffix in (("p1", ""), ("p1_load", "_load")):
        if column not in probes:
            continue
        p = [v / P_SCALE for v in probes[column]]
        o = onset(t, p)
        m.update({column: p, "onset" + suffix: o, "plateau" + suffix: plateau(t, p),
                  "impulse" + suffix: impulse(t, p, o, IMPULSE_WINDOW) if math.isfinite(o) else float("nan")})
    return m


def reference_measures():
    """The experiment's impact, plateau and P2 wetting time, and the delta-SPH's impact, plateau, impulse and
    P2 wetting time."""
    exp1, sph1, sph2 = references()
    e_on = onset(exp1["t_star"], exp1["p_star"])
    s_on = onset(sph1["t_star"], sph1["p_dSPH_H320"])
    return {"exp_onset": e_on, "exp_plateau": plateau(exp1["t_star"], exp1["p_star"]),
            "exp_impulse": impulse(exp1["t_star"], exp1["p_star"], e_on, IMPULSE_WINDOW),
            "exp_p2_wets": wets(sph2["t_star"], sph2["p_exp"]),
            "sph_onset": s_on, "sph_plateau": plateau(sph1["t_star"], sph1["p_dSPH_H320"]),
            "sph_impulse": impulse(sph1["t_star"], sph1["p_dSPH_H320"], s_on, IMPULSE_WINDOW),
            "sph_p2_wets": wets(sph2["t_star"], sph2["p_dSPH_H320"])}
