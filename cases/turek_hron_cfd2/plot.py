"""Turek & Hron (2006) CFD2: the drag and the lift of the rigid cylinder with its flag, time means over the last
1 s of the run (the flow is steady at Re = 100; the means remove the noise of the remeshing), against the
benchmark's values (reference/turek_hron_2006_cfd2.csv). Records: drag, lift (N/m: the cylinder's and the flag's
forces added), drag_std, lift_std (their standard deviations over the window), drag_cylinder, lift_cylinder (the
cylinder's share), discharge (the flow rate at x = 1.5 m over the inflow's 0.41 m^2/s, same window).
Usage: /usr/bin/python3 cases/turek_hron_cfd2/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
from lagfsi_post import out_dir_from_argv  # noqa: E402
from turek_hron import cfd_forces  # noqa: E402

cfd_forces(out_dir_from_argv("out/turek_hron_cfd2"), os.path.dirname(os.path.abspath(__file__)), "CFD2", window=1.0,
           q_in=1.0 * 0.41, lift_span=20.0)
