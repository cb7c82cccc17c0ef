#pragma once
/// @file solid/solid_model.hpp
/// The solid and shell bodies ("type": "solid" | "shell") as PhysicsModels: positional FEM (the bodies'
/// kernels: lagfsi/solid.hpp, lagfsi/shell.hpp) with boundary conditions, loads, Newton iterations with a
/// time integrator (or load stepping for static analysis), probes and output; also the structure side of
/// the FSI coupling (InterfaceStructure, interface.hpp).
///
/// The module's model files (src/solid), one concern per file:
///  - the SolidModel class (private)                                     solid_model_impl.hpp
///  - reading the body: material, geometry, mesh, damping, boundary conditions, loads   solid_input.cpp
///  - a step's Newton iterations: residual, tangent, follower loads, damping, factorization   solid_newton.cpp
///  - the lifecycle (initialize, predict, finalize_step, output) and the coupling   solid_model.cpp
///  - probes: displacement / position, reaction, energy                  solid_probes.cpp
///  - the bodies' kernels                                  solid_body.cpp, shell_body.cpp, structure.cpp
#include <lagfsi/case.hpp>
#include <lagfsi/model.hpp>

#include <memory>

namespace lagfsi {

/// The solid or shell body's builder (registered as "solid" and "shell" in model_registry() of the app
/// layer, model_registry.hpp). Reads the body (its case-file object); throws InputError for a bad body.
std::unique_ptr<PhysicsModel> make_solid_model(Params body, const CaseContext& ctx);

}  // namespace lagfsi
