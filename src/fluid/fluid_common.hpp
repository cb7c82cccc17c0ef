#pragma once
/// @file fluid_common.hpp (private to src/fluid)
/// What every piece of the PFEM fluid shares: the particle kinds and the fluid's constants (FluidConstants,
/// src/fluid/include/lagfsi/fluid/fluid_params.hpp, read once by the model's constructor in fluid_input.cpp) and the
/// phase clock (lagfsi/stopwatch.hpp).
#include <lagfsi/error.hpp>
#include <lagfsi/fluid/fluid_params.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/stopwatch.hpp>
#include <lagfsi/types.hpp>

#include <string>
