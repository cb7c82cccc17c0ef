#!/usr/bin/env bash
# Sets up the machine, builds, and runs the whole test suite (unit, verification, regression).
# Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
start=$(date +%s)
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh"
cd "$root/build"
status=0
ctest --output-on-failure -j "${LAGFSI_TEST_JOBS:-2}" "$@" || status=$?
echo "test.sh: set-up, build and tests took $(( $(date +%s) - start )) s"
exit $status
