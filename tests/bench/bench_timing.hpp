#pragma once
// Timing helpers shared by the benchmarks in tests/bench (wall clock, best of n runs).
#include <algorithm>
#include <chrono>
#include <type_traits>

namespace lagfsi::bench {

using Clock = std::chrono::steady_clock;

/// Wall-clock seconds since t0.
inline double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The shortest of n timed calls of f (f() or f(i) with the run's index i).
template <class F>
double best_of(int n, F&& f) {
  double best = 1e300;
  for (int i = 0; i < n; ++i) {
    const auto t0 = Clock::now();
    if constexpr (std::is_invocable_v<F&, int>)
      f(i);
    else
      f();
    best = std::min(best, seconds(t0));
  }
  return best;
}

}  // namespace lagfsi::bench
