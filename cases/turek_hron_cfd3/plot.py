"""Turek & Hron (2006) CFD3: the periodic drag and lift of the rigid cylinder with its flag (Re = 200, vortex
shedding) against the benchmark's mean, amplitude and frequency (reference/turek_hron_2006_cfd3.csv), over the
last 2 s of the run (the last half of a shorter one), with the flapping flag's conventions (cases/tools/turek_hron.py,
cfd_oscillation): the lift's frequency from its periodogram, the means and amplitudes of the phase average after a
centred running mean over 0.02 s (a tenth of a period), which removes the remeshing's step-to-step noise.
Records: drag_mean, drag_amplitude, lift_mean, lift_amplitude, lift_frequency, drag_raw_amplitude,
lift_raw_amplitude, lift_noise (N/m, Hz).
Usage: /usr/bin/python3 cases/turek_hron_cfd3/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
from lagfsi_post import out_dir_from_argv  # noqa: E402
from turek_hron import cfd_oscillation  # noqa: E402

cfd_oscillation(out_dir_from_argv("out/turek_hron_cfd3"), os.path.dirname(os.path.abspath(__file__)), "CFD3",
                window=2.0, smooth=0.02)
