"""Small post-processing helpers shared by the case plot scripts (run with /usr/bin/python3)."""
import csv
import math
import os
import sys


def read_csv(path):
    """Reads a CSV with a header row (lines starting with '#' skipped) into a dict of float lists."""
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith('#'))]
    header, data = rows[0], rows[1:]
    cols = {h: [] for h in header}
    for r in data:
        for h, v in zip(header, r):
            try:
                cols[h].append(float(v))
            except ValueError:
                cols[h].append(v)
    return cols


def out_dir_from_argv(default):
    return sys.argv[1] if len(sys.argv) > 1 else default


def last_period_stats(t, u):
    """Turek & Hron's convention for a periodic signal: mean = (max + min)/2 and amplitude = (max - min)/2
    over the last full period; frequency from the mean spacing of the upward crossings of the mid-level
    (linear interpolation between samples), which is robust to high-frequency ripple."""
    mid = 0.5 * (max(u) + min(u))
    band = 0.1 * (max(u) - min(u))  # hysteresis against ripple
    ups, armed = [], False
    for i in range(1, len(u)):
        if u[i] < mid - band:
            armed = True
        if armed and u[i - 1] < mid <= u[i]:
            ups.append(t[i - 1] + (mid - u[i - 1]) / (u[i] - u[i - 1]) * (t[i] - t[i - 1]))
            armed = False
    if len(ups) < 2:
        return None
    seg = [uu for tt, uu in zip(t, u) if ups[-2] <= tt <= ups[-1]]
    umax, umin = max(seg), min(seg)
    period = (ups[-1] - ups[0]) / (len(ups) - 1)
    return {"mean": 0.5 * (umax + umin), "amplitude": 0.5 * (umax - umin), "frequency": 1.0 / period,
            "periods": len(ups) - 1}


def save(fig, out_dir, name="comparison.png"):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print("wrote", path)
