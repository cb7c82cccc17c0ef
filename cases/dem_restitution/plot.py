#!/usr/bin/python3
"""dem_restitution: rebound / impact speed of a disc on a rigid floor at 0.05, 0.5 and 5 m/s for the linear
spring-dashpot and Hertz-Mindlin (Tsuji damping) laws, against the restitution coefficient asked for (0.5 in
case.json; run with --set bodies.0.contact.restitution=E --set bodies.1.contact.restitution=E for others).

usage: /usr/bin/python3 cases/dem_restitution/plot.py OUTDIR [E]
"""
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from claims_record import record  # noqa: E402  (numbers for scripts/claims.py)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "out")
    e = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5
    with open(os.path.join(out, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    last = rows[-1]
    speeds = [("v005", 0.05), ("v05", 0.5), ("v5", 5.0)]
    fig, ax = plt.subplots(figsize=(6, 4))
    for law, mk in (("linear", "o"), ("hertz", "s")):
        got = [float(last[f"{law}_{c}"]) / v for c, v in speeds]
        for (c, v), g in zip(speeds, got):
            record(f"{law}_{c}", g)
            print(f"{law:7s} impact {v:5.2f} m/s: restitution {g:.5f} (asked {e}, {100 * (g / e - 1):+.3f} %)")
        ax.semilogx([v for _, v in speeds], got, mk + "-", label=law)
    ax.axhline(e, color="k", ls="--", lw=0.8, label="asked")
    ax.set_ylim(e * 0.95, e * 1.05)
    ax.set_xlabel("impact speed [m/s]")
    ax.set_ylabel("restitution coefficient")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "comparison.png"), dpi=110)


if __name__ == "__main__":
    main()
