#!/usr/bin/env bash
# Sets up the machine, builds, runs the default case, draws its comparison plot and its pictures.
# Output: out/<case>/ (ParaView: <body>.pvd, paraview_state.py; probes.csv, log.csv, summary.json),
# out/<case>/comparison.png, and the pictures of scripts/snapshots.py: out/<case>/snapshots.png (a strip of five
# times), out/<case>/animation.gif (and animation.mp4 when ffmpeg is installed), out/<case>/snapshots/*.png.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
case_name=${1:-dam_break_tank}
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" lagfsi   # the executable alone: the tests are built by scripts/test.sh
cd "$root"
"$root/build/lagfsi" run "cases/$case_name/case.json" -o "out/$case_name"
/usr/bin/python3 "cases/$case_name/plot.py" "out/$case_name"
/usr/bin/python3 "$root/scripts/snapshots.py" "out/$case_name" --quiet
echo "plot: out/$case_name/comparison.png   pictures: out/$case_name/snapshots.png, out/$case_name/animation.gif"
echo "ParaView: paraview --state=out/$case_name/paraview_state.py   (or the series out/$case_name/*.pvd)"
