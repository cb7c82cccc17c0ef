#pragma once
// Everything the schemes of an MPM body work on (read by mpm_input.cpp, advanced by the schemes): the
// material, the grid and its shape functions, the particles and their supports, the grid's boundary
// conditions, the particle loads, damping and two-phase properties, and the body's clock.
#include "mpm_boundaries.hpp"

#include <lagfsi/error.hpp>
#include <lagfsi/mpm/mpm_material.hpp>
#include <lagfsi/mpm/mpm_state.hpp>

#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace lagfsi::mpm {

/// Damping of the explicit schemes: Cundall local damping (a share of the node's unbalanced force against its
/// motion, before local_until) and Rayleigh damping (alpha M v on the grid, beta C : (strain rate) on the
/// particles).
struct Damping {
  double local = 0;
  double local_until = std::numeric_limits<double>::infinity();  // local damping only before this time
  double mass = 0, stiffness = 0;
};

/// Saturated two-phase bodies: water density, bulk modulus, hydraulic conductivity (m/s); grains
/// incompressible (the material's density is the grains').
struct WaterProperties {
  double density = 1000, bulk_modulus = 2.2e9, conductivity = 1e-3;
};

struct MpmBody {
  std::string name;
  std::string grid_path;  // the body's "grid" in the case file (/bodies/i/grid), for the errors about it
  std::unique_ptr<MpmMaterial> material;
  Grid grid;
  ShapeFunctions shape;
  Particles particles;
  std::vector<Support> support;  // of every particle, at the last sub-step
  GridBoundaries boundaries;
  std::vector<ParticleLoad> loads;
  Damping damping;
  double flip = 1.0;  // FLIP share of the particle velocity update (1: FLIP; 0: PIC, the grid velocity)
  double cfl = 0.5;   // explicit sub-step cfl h / c
  bool two_phase = false;
  WaterProperties water;
  Vec2 case_gravity = Vec2::Zero();  // the case's gravity
  bool gravity_on = true;            // the body's "gravity" switch
  double t = 0;                      // time of the particles' state
  double gravity_work = 0;           // work of gravity since the start

  /// Gravity acting on the body (zero when switched off).
  Vec2 gravity() const { return gravity_on ? case_gravity : Vec2::Zero(); }
  /// Supports of every particle at its current position; throws SolverError naming the grid's JSON path when
  /// one has left the grid (the grid's edges are free: nothing holds a body that reaches them but the
  /// boundary conditions given).
  void locate_particles() {
    const Index outside = mpm::locate_particles(grid, shape, particles, support);
    if (outside < 0) return;
    const Vec2 x = particles.x[outside], hi = grid.origin + grid.h * Vec2(grid.nx, grid.ny);
    std::ostringstream os;
    os << grid_path << ": body '" << name << "': particle " << outside << " left the grid (x " << grid.origin.x()
       << ".." << hi.x() << ", y " << grid.origin.y() << ".." << hi.y() << ") at (" << x.x() << ", " << x.y()
       << "), t = " << t << ": the grid's edges are free; a larger grid, or boundary conditions that hold the body";
    throw SolverError(os.str());
  }
  /// "body 'NAME': particle P WHAT at t = T".
  SolverError particle_error(Index p, const std::string& what) const {
    return SolverError("body '" + name + "': particle " + std::to_string(p) + " " + what +
                       " at t = " + std::to_string(t));
  }
};

/// What a step changes in a body (the retry snapshot of MpmModel::predict): the particles, their supports,
/// the boundaries (the free-field columns' state), the clock and the gravity work. The grid is rebuilt from
/// the particles at every sub-step.
struct MpmStepSnapshot {
  Particles particles;
  std::vector<Support> support;
  GridBoundaries boundaries;
  double t = 0, gravity_work = 0;
  void save(const MpmBody& b) {
    particles = b.particles;
    support = b.support;
    boundaries = b.boundaries;
    t = b.t;
    gravity_work = b.gravity_work;
  }
  void restore(MpmBody& b) const {
    b.particles = particles;
    b.support = support;
    b.boundaries = boundaries;
    b.t = t;
    b.gravity_work = gravity_work;
  }
};

}  // namespace lagfsi::mpm
