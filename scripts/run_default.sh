#!/usr/bin/env bash
# Sets up the machine, builds, runs the default case and draws its comparison plot.
# Output: out/<case>/ (ParaView: <body>.pvd; probes.csv, log.csv, summary.json) and out/<case>/comparison.png.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
case_name=${1:-dam_break_tank}
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh"
cd "$root"
"$root/build/lagfsi" run "cases/$case_name/case.json" -o "out/$case_name"
/usr/bin/python3 "cases/$case_name/plot.py" "out/$case_name"
echo "ParaView: out/$case_name/*.pvd   plot: out/$case_name/comparison.png"
