#pragma once
/// @file fluid_defaults.hpp (private to src/fluid)
/// The fluid's defaults that follow from other keys: its preset and the keys the preset decides (fluid_defaults.cpp;
/// docs/fluid_settings.md, "How the defaults follow from each other").
#include <lagfsi/params.hpp>

#include <string>

namespace lagfsi::fluid {

// The defaults that depend on other keys (docs/fluid_settings.md, "How the defaults follow from each other"). With
// the monolithic scheme and remeshing they are conservative: the previous domain advected with
// the particles decides which new triangles are fluid, rigid walls are constraints on the fluid particles on them,
// sliding against their Navier friction, the free-surface pressure is held weakly (Robin) and each particle keeps its
// own area (measured in cases/dam_break_tank, cases/dam_break_obstacle, cases/sloshing_free and the FSI cases). The
// fractional step has no particle volumes (below), and a fixed mesh does not remesh: they, and a case that
// chooses "alpha", keep the classic PFEM defaults: the alpha shape, wall particles, p = 0 on the free surface
// and the surface correction. The peek reads a key only when it has the right type; the validation below
// reports any other value.
struct FluidDefaults {
  std::string preset, detection, wall_model, wall_friction, free_surface_pressure, volume_correction;
  double contact_gap = 0.0, volume_relaxation_time = 0.1;
};

/// The defaults of a fluid body's JSON (read before it is validated: a key of the wrong type is left to the
/// validation, which reports it).
FluidDefaults fluid_defaults(const Json& body);

/// The string o[key], or `fallback` when o has no such string.
std::string peek(const Json& o, const char* key, const std::string& fallback);

}  // namespace lagfsi::fluid
