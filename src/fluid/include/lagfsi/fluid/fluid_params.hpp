#pragma once
/// @file fluid/fluid_params.hpp
/// The PFEM fluid's parameters, read once from its case-file object (/bodies/i of type "fluid") by the
/// model's constructor (src/fluid/fluid_input.cpp) and handed to the pieces that use them: the constants of
/// the fluid, the remeshing's settings and each scheme's.
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/meshing/remesh.hpp>
#include <lagfsi/types.hpp>

#include <string>

namespace lagfsi::fluid {

using meshing::ParticleKind;

/// The fluid's material and discretization constants and the case's settings the pieces read.
struct FluidConstants {
  std::string name;  // the body's name (error messages, output files)
  double rho = 1000, mu = 1e-3;
  // The case's "spacing": the size of the particles it creates (the initial ones unless a size field grades them,
  // those of walls, structures and open boundaries, where an adaptive size field keeps its finest size) and the
  // yardstick of tolerances (convergence, contacts). A particle's own size, wherever the geometry needs one (merge
  // radii, flat elements, insertions, the step limit, a drop's mass), is ParticleCloud::h(i).
  double h = 0.01;
  bool remesh = true;   // PFEM mode (remeshed every step) or fixed connectivity
  double bulk = 2.2e9;  // bulk modulus of the slight compressibility (0: incompressible)
  Vec2 gravity = Vec2::Zero();
  double wall_snap_fraction = 0.1;  // "wall_model": "constraints": a particle approaching a wall closer than
                                    // this * h is put on it (WallContacts::snap_to_walls)
};

/// The remeshing's settings (/bodies/i and /bodies/i/scheme; RemeshPipeline, remesh_pipeline.hpp).
struct FluidRemeshSettings {
  double alpha = 1.2;           // alpha shape: delete an element with circumradius above alpha * h
  double close_fraction = 0.3;  // remove a fluid particle closer than this * h to another particle
  double flat_fraction = 0.01;  // drop elements with area below this * h^2
  double insert_factor = 1.0;   // insert a particle at the centroid of elements larger than this * h^2
  double domain_margin = 0.1;   // the domain box: walls and initial fluid, enlarged by this * larger side
  meshing::DomainDetection detection = meshing::DomainDetection::Alpha;
  double separation_alpha = 2.5;  // advected / level set: an inside element is torn off when R > this h
  double level_set_band = 0.25;   // level set: outside elements within this h of the previous boundary
  double contact_gap = 0.0;       // advected / level set: surfaces join when their gap is at most this h
                                  // (meshing::RemeshSettings::contact_gap; 0: off)
  double split_factor = 1.6;      // advected / level set: split free-surface edges longer than this h
  double keep_edges_angle = 0.0;  // advected / level set: hysteresis of the Delaunay flips, radians
                                  // (meshing::RemeshSettings::keep_edges_angle; input in degrees)
};

/// The free-surface pressure: p = 0 prescribed, traction-free in the weak form, or the Robin condition
/// (fluid_element.hpp).
enum class FreeSurfacePressure { dirichlet, natural, robin };

/// The monolithic PSPG scheme's settings (/bodies/i/scheme).
struct PspgSettings {
  double tau_U = 0;    // 0: automatic tau; > 0: Tezduyar's velocity scale U ("velocity_scale")
  bool lumped = true;  // lumped or consistent mass
  FreeSurfacePressure free_surface = FreeSurfacePressure::dirichlet;  // "free_surface_pressure"
  double robin_factor = 0.04;  // the Robin condition's weight f over the FIC one ("robin_factor"; a tuned value)
  double tol = 1e-4;
  int refactor_every = 0;       // 0: one factorization per step (the matrix barely changes within a
                                // step); k >= 1: refactorized every k iterations (1: Newton)
  LinearSolverSettings solver;  // the Newton system's ("linear_solver"; kind saddle_point, block size 3)
};

/// The fractional step's settings (/bodies/i/scheme).
struct FractionalStepSettings {
  std::string viscous_step = "automatic";  // automatic | explicit | implicit
  LinearSolverSettings solver;   // the pressure Poisson's ("linear_solver"; kind symmetric_positive_definite); the
                                 // implicit viscous predictor's is the same with kind mass_dominated
  bool retry_inverted = true;    // an element inverted within the step fails it (retry)
  bool exact_area_rate = false;  // the pressure equation holds each element's exact area rate (advected, level set)
  bool consistent_mass = false;  // the predictor with the consistent mass matrix off the free surface ("mass")
};

}  // namespace lagfsi::fluid
