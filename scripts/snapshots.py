#!/usr/bin/python3
"""Pictures of a lagfsi output folder without ParaView (snapshots, strip, animation, ParaView state).

usage: scripts/snapshots.py OUTDIR [--field pressure|velocity|von_mises|damage|displacement|...]
                                   [--times T1,T2,...] [--count N] [--frames N] [--range VMIN,VMAX]
                                   [--box XMIN,XMAX,YMIN,YMAX]
                                   [--fluid mesh|particles] [--cmap NAME] [--dpi D] [--out DIR]
                                   [--no-animation] [--no-mp4] [--no-state] [--quiet]

Writes OUTDIR/snapshots.png (strip), OUTDIR/snapshots/*.png (one per time), OUTDIR/animation.gif (and
animation.mp4 with ffmpeg) and OUTDIR/paraview_state.py. See cases/tools/lagfsi_post/snapshots.py (or --help).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "tools"))
from lagfsi_post.snapshots import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
