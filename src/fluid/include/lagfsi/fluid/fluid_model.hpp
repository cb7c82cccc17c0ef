#pragma once
/// @file fluid/fluid_model.hpp
/// The PFEM fluid body ("type": "fluid"): particles carrying positions, velocities, accelerations and
/// pressure; the mesh is rebuilt from the particles at every step (Delaunay + domain detection: the alpha
/// shape, or the advected previous domain of the conservative remeshing) or kept fixed; a step is solved by
/// the scheme chosen in the case: the monolithic PSPG position-pressure system (Avancini 2018, ch. 6) or a
/// fractional step (incremental pressure correction, Chorin 1968, Goda 1979). Plane, unit thickness. It is
/// also the fluid side of the FSI coupling (InterfaceFluid, interface.hpp: ghost particles on a structure's
/// wet boundary).
///
/// The module (public headers in src/fluid/include/lagfsi/fluid, the rest in src/fluid), one concern per file:
///  - the parameters read from the case (constants, remeshing, schemes)   fluid_params.hpp
///  - the particles' arrays (compact, append, rebuild)                   particle_cloud.hpp, particle_cloud.cpp
///  - the step's mesh and its queries                                    fluid_mesh.hpp, fluid_mesh.cpp
///  - rigid walls: particles or constraints, motion, keep_inside_walls  fluid_walls.hpp, fluid_walls.cpp
///  - ghost particles of a coupled structure                            ghosts.hpp, ghosts.cpp
///  - the remesh of a step: domain box, Delaunay + domain detection and its filters, close/insert
///    particles (alpha)                                                  remesh_pipeline.hpp, remesh_pipeline.cpp
///  - conservative remeshing: the advected domain, particle management  particle_management.cpp
///  - area bookkeeping and the volume corrections ("surface", "source") volume_correction.hpp, .cpp
///  - energies: kinetic, potential, gravity work, dissipation, boundary work   fluid_energy.hpp, .cpp
///  - the pressure level of incompressible water no boundary sets        pressure_level.hpp, .cpp
///  - the schemes, chosen once per body (fluid_scheme.hpp): monolithic PSPG (pspg_scheme.cpp), fractional
///    step (fractional_step.cpp; its prescribed particles' forces fractional_step_reactions.hpp, .cpp, its
///    consistent mass's solver masked_cg.hpp, .cpp); the element kernel fluid_element.cpp (fluid_element.hpp)
///  - reading the body from the case                                     fluid_input.cpp, point_grid.hpp
///  - probes                                                             fluid_probes.hpp, fluid_probes.cpp
///  - the PhysicsModel lifecycle (the model over its pieces)            fluid_model_impl.hpp, fluid_model.cpp
#include <lagfsi/case.hpp>
#include <lagfsi/fluid/fluid_params.hpp>
#include <lagfsi/model.hpp>

#include <memory>

namespace lagfsi {

/// The fluid body's builder (registered as "fluid" in model_registry() of the app layer, model_registry.hpp). Reads the
/// body (its case-file object), builds its walls, particles and scheme; throws InputError for a bad body.
std::unique_ptr<PhysicsModel> make_fluid_model(Params body, const CaseContext& ctx);

/// The analysis integrator a fluid body (its case-file object) asks for when the case names none: generalized-alpha
/// (rho_inf = 0.8) for the monolithic scheme with the Robin free-surface pressure and the walls as constraints (the
/// conservative package's, its default with remeshing), whose pressure alternates from one step to the next under
/// the trapezoidal rule (docs/fluid_settings.md); null otherwise (the analysis' Newmark; with wall particles
/// the trapezoidal rule lets less water through the walls). Reads what it needs leniently: a bad body is
/// reported by make_fluid_model.
Json fluid_preferred_integrator(const Json& body);

}  // namespace lagfsi
