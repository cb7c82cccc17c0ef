#!/usr/bin/env bash
# Configures and builds lagfsi (Release) in ./build. Used by run_default.sh and test.sh.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${LAGFSI_JOBS:-$(nproc)}
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j "$jobs"
