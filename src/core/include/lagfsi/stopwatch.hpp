#pragma once
/// @file stopwatch.hpp
/// Wall-clock seconds since a time point of the steady clock: the phase times of a step, the run's wall time.
#include <chrono>

namespace lagfsi {

using SteadyClock = std::chrono::steady_clock;

inline double seconds_since(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

}  // namespace lagfsi
