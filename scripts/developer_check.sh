#!/usr/bin/env bash
# The Developer build (CMakePresets.json): warnings as errors (-Wall -Wextra -Werror) and
# AddressSanitizer + UndefinedBehaviorSanitizer, in ./build-dev; then the unit and verification tiers under the
# sanitizers (a sanitizer report fails the test: halt_on_error). CI keeps the Release build (scripts/test.sh).
# First of all, the tree must be formatted as .clang-format says (clang-format --dry-run -Werror; a few seconds).
# Usage: scripts/developer_check.sh [ctest arguments, e.g. -R Retry]; LAGFSI_JOBS sets the build's parallelism.
# The last runs, with their commits, are in docs/testing.md (Developer build).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${LAGFSI_JOBS:-$(nproc)}
cd "$root"
if command -v clang-format >/dev/null; then
  git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format --dry-run -Werror ||
    { echo "developer_check: sources not formatted; run: git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format -i" >&2; exit 1; }
fi
cmake --preset Developer >/dev/null
cmake --build --preset Developer -j "$jobs"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --preset Developer -j "${LAGFSI_TEST_JOBS:-2}" --output-on-failure "$@"
