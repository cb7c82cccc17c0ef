"""Turek & Hron (2006) FSI3: the flag's oscillation behind the cylinder at Re = 200 against the benchmark's values
(reference/turek_hron_2006_fsi3.csv), as mean = (max + min)/2 and amplitude = (max - min)/2 over a period and the
frequency, in the last 2 s of the run (the last half of a shorter one).
The statistics are FSI2's (cases/tools/turek_hron.py, fsi_oscillation): the tip's displacements by the benchmark's
convention (the extremes of the last full period, the frequency from the spacing of the mid-level's upward crossings
in the window); the forces (drag and lift: the cylinder's wall force and the coupling's interface force added), noisy
step by step (the remeshing's insertions and removals), by the extremes of their phase average over the whole
periods of u_y(A) that end the window (40 phase bins) after a centred running mean over 0.01 s (a ninth of the
drag's period of about 0.09 s; drag_raw_amplitude and lift_raw_amplitude without it), their frequency the peak of the
window's periodogram over 0.5-20 Hz (steps of 0.001 Hz: the drag's 10.9 Hz inside). When u_y(A) does not cross its
mid-level twice in the window (a short run's start-up), every mean and amplitude is (max + min)/2 and
(max - min)/2 over the window and the tip's frequencies are 0.
Records the same numbers as turek_hron_fsi2's plot.py (ux_A_mean ... lift_frequency, drag_raw_amplitude,
lift_raw_amplitude, iterations, iterations_window, iterations_max).
Usage: /usr/bin/python3 cases/turek_hron_fsi3/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
from lagfsi_post import out_dir_from_argv
from turek_hron import fsi_oscillation

WINDOW = 2.0  # s, the window of the statistics at the end of the run (about ten periods of u_y)
SMOOTH = 0.01  # s, the forces' centred running mean

fsi_oscillation(out_dir_from_argv("out/turek_hron_fsi3"), os.path.dirname(__file__), "FSI3", WINDOW, SMOOTH,
                band=(0.5, 20.0))
