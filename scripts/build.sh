#!/usr/bin/env bash
# Configures and builds lagfsi (Release) in ./build, on every core. Used by run_default.sh and test.sh.
# Arguments are build targets (e.g. `lagfsi`, the executable alone); none builds everything (tests included).
# LAGFSI_JOBS sets the parallelism; a ccache on the PATH is used when present.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${LAGFSI_JOBS:-$(nproc)}
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$root/build" -j "$jobs" "${targets[@]}"
