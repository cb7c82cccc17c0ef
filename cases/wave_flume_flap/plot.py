"""Regular waves from a flap paddle hinged on the floor (linear wave-maker theory) against linear wave theory at the
gauges x = 1.5 and 2.5 m (cases/tools/wave_flume.py: wave heights, period, phase speed, area drift).
Usage: /usr/bin/python3 cases/wave_flume_flap/plot.py OUTDIR (the picture is named after OUTDIR's last part)"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tools"))
from lagfsi_post import out_dir_from_argv
from wave_flume import analyse

analyse("wave_flume_flap", out_dir_from_argv("out/wave_flume_flap"),
        os.path.join(os.path.dirname(__file__), "reference", "linear_theory.csv"), depth=0.4, flume=8.0)
