#pragma once
/// @file model_registry.hpp
/// The app layer's registry of body types (lagfsi::app, defined in src/app/case_builder.cpp): a small explicit map
/// from a body's "type" string to its module's builder. A new model adds one line there and links its module
/// into lagfsi::app (src/CMakeLists.txt); the core and the other modules do not know it.
#include <lagfsi/case.hpp>
#include <lagfsi/dem/dem_model.hpp>
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/fluid/fluid_model.hpp>
#include <lagfsi/mpm/mpm_model.hpp>
#include <lagfsi/solid/solid_model.hpp>

#include <functional>
#include <map>
#include <string>

namespace lagfsi {

/// "solid", "shell" (make_solid_model), "fluid", "mpm", "dem", "efg" (element-free Galerkin).
const std::map<std::string, ModelBuilder>& model_registry();

/// What a body type asks of the analysis' integrator when the case names none: the model's own function of its
/// body's settings, giving an integrator object ({"type": ..., ...}) or null (no preference). The fluid asks for
/// generalized-alpha with the Robin free-surface pressure and walls as constraints (fluid_preferred_integrator).
using IntegratorPreference = std::function<Json(const Json& body)>;
const std::map<std::string, IntegratorPreference>& integrator_preferences();

}  // namespace lagfsi
