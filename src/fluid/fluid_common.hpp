#pragma once
/// @file fluid_common.hpp (private to src/fluid)
/// What every piece of the PFEM fluid shares: the particle kinds and the fluid's constants (FluidConstants,
/// src/fluid/include/lagfsi/fluid/fluid_params.hpp, read once by the model's constructor in fluid_input.cpp) and the
/// phase clock.
#include <lagfsi/error.hpp>
#include <lagfsi/fluid/fluid_params.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/types.hpp>

#include <chrono>
#include <string>

namespace lagfsi::fluid {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace lagfsi::fluid
