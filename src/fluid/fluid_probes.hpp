#pragma once
/// @file fluid_probes.hpp (private to src/fluid)
/// The probes of a fluid body (/probes/i with "body" a fluid): front, column_height, elevation, pressure, wall_force,
/// fluid_area and the energies.
#include <lagfsi/model.hpp>
#include <lagfsi/params.hpp>

#include <memory>
#include <string>

namespace lagfsi::fluid {

class FluidModel;

/// A probe of `m` of type `type` (checked by FluidModel::make_probe) named `name`; its keys are checked here.
std::unique_ptr<Probe> make_fluid_probe(const FluidModel& m, std::string name, std::string type, Params p);

}  // namespace lagfsi::fluid
