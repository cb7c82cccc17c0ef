"""Turek & Hron (2006) FSI2: the flag's oscillation behind the cylinder at Re = 100 against the benchmark's values
(reference/turek_hron_2006_fsi2.csv), as mean = (max + min)/2 and amplitude = (max - min)/2 over a period and the
frequency, in the last 4 s of the run (the last half of a shorter one).
The statistics are cases/tools/turek_hron.py's fsi_oscillation: the tip's displacements by the benchmark's convention
(the extremes of the last full period, the frequency from the spacing of the mid-level's upward crossings in the
window); the forces (drag and lift: the cylinder's wall force and the coupling's interface force added), noisy step
by step (the remeshing's insertions and removals), by the extremes of their phase average over the whole periods of
u_y(A) that end the window (40 phase bins) after a centred running mean over 0.025 s (ten steps of 2.5 ms, a tenth of
the drag's period; drag_raw_amplitude and lift_raw_amplitude without it), their frequency the peak of the window's
periodogram over 0.5-10 Hz (steps of 0.001 Hz). When u_y(A) does not cross its mid-level twice in the window (a
short run's start-up), every mean and amplitude is (max + min)/2 and (max - min)/2 over the window and the tip's
frequencies are 0.
Records: ux_A_mean, ux_A_amplitude, ux_A_frequency, the same for uy_A, drag and lift (m, N/m, Hz),
drag_raw_amplitude, lift_raw_amplitude, iterations (coupling passes per step, mean over the run), iterations_window
(over the window), iterations_max.
Usage: /usr/bin/python3 cases/turek_hron_fsi2/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
from lagfsi_post import out_dir_from_argv
from turek_hron import fsi_oscillation

WINDOW = 4.0  # s, the window of the statistics at the end of the run (about eight periods of u_y)
SMOOTH = 0.025  # s, the forces' centred running mean

fsi_oscillation(out_dir_from_argv("out/turek_hron_fsi2"), os.path.dirname(__file__), "FSI2", WINDOW, SMOOTH,
                band=(0.5, 10.0))
