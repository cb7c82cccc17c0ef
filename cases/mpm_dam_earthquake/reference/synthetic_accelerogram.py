#!/usr/bin/python3
"""Writes synthetic_accelerogram.csv: a 60 s horizontal accelerogram standing in for the Lima 1974 N82W record
of the thesis (not available here), scaled to PGA = 0.38 g, starting at t = t0 (after the static phase).

Method (stochastic, the classical engineering construction; fixed seed, so the file is reproducible):
  1. Gaussian white noise, dt = 0.01 s, seed 1974.
  2. Envelope of Saragoni & Hart (1974): e(t) = a (t/tn)^b exp(-c t/tn) with its peak at 0.2 of the 60 s
     duration (b = 2, c = b / 0.2 = 10, tn = 60 s).
  3. Filter of Kanai & Tajimi with the high-pass of Clough & Penzien (1975), applied in the frequency domain:
     H = (wg^2 + 2 i zg wg w) / (wg^2 - w^2 + 2 i zg wg w) * w^2 / (wf^2 - w^2 + 2 i zf wf w), firm soil
     wg = 5 pi rad/s (2.5 Hz), zg = 0.6; wf = 0.1 wg, zf = 0.6.
  4. Baseline correction: the acceleration minus the derivative of a cubic fitted to the velocity (least
     squares), cosine tapers of 1 s at both ends, and a linear correction c0 + c1 t within the tapers that
     brings the final velocity and displacement to zero.
  5. Scaled to PGA = 0.38 g (g = 9.81 m/s^2; scaling and the linear correction alternate three times).
Columns: time [s], acceleration [m/s^2]. Any user record in the same two-column form can replace it.
Usage: /usr/bin/python3 synthetic_accelerogram.py [t0=10]"""
import math
import os
import sys

import numpy as np

t0 = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
dt, T, pga = 0.01, 60.0, 0.38 * 9.81
n = int(round(T / dt)) + 1
t = np.arange(n) * dt
rng = np.random.default_rng(1974)
noise = rng.standard_normal(n)
b, c = 2.0, 10.0
env = (t / T) ** b * np.exp(-c * t / T)
x = noise * env / env.max()
w = 2 * math.pi * np.fft.rfftfreq(n, dt)
wg, zg = 5 * math.pi, 0.6
wf, zf = 0.1 * wg, 0.6
H = (wg ** 2 + 2j * zg * wg * w) / (wg ** 2 - w ** 2 + 2j * zg * wg * w) * w ** 2 / (wf ** 2 - w ** 2 + 2j * zf * wf * w)
a = np.fft.irfft(np.fft.rfft(x) * H, n)
v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
coef = np.polyfit(t, v, 3)
a = a - np.polyval(np.polyder(coef), t)
taper = np.ones(n)
k = int(1.0 / dt)
taper[:k] = 0.5 * (1 - np.cos(np.pi * np.arange(k) / k))
taper[-k:] = taper[:k][::-1]
a *= taper
def integrate(y):
    return np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * dt)])


# A linear correction c0 + c1 t (inside the tapered window) brings the final velocity and displacement to zero.
for _ in range(3):
    a *= pga / np.abs(a).max()
    basis = [taper * np.ones(n), taper * t]
    M = np.array([[integrate(bf)[-1], integrate(integrate(bf))[-1]] for bf in basis]).T
    rhs = -np.array([integrate(a)[-1], integrate(integrate(a))[-1]])
    c0, c1 = np.linalg.solve(M, rhs)
    a = a + c0 * basis[0] + c1 * basis[1]
v = integrate(a)
d = integrate(v)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "synthetic_accelerogram.csv")
with open(out, "w") as f:
    f.write("# Synthetic accelerogram (synthetic_accelerogram.py: Saragoni-Hart envelope, Kanai-Tajimi/Clough-Penzien\n")
    f.write("# filter, seed 1974, baseline-corrected), 60 s, PGA 0.38 g, starting at t = %g s. Final velocity %.2e m/s,\n"
            % (t0, v[-1]))
    f.write("# final displacement %.2e m. Columns: time [s], horizontal acceleration [m/s^2].\n" % d[-1])
    f.write("time,acceleration\n")
    for ti, ai in zip(t, a):
        f.write("%.2f,%.6e\n" % (ti + t0, ai))
print("wrote %s: PGA %.3f m/s^2, final velocity %.2e m/s, final displacement %.3f m, peak velocity %.3f m/s"
      % (out, np.abs(a).max(), v[-1], d[-1], np.abs(v).max()))
