#pragma once
/// @file fluid_energy.hpp (private to src/fluid)
/// The fluid's energy balance for the probes: kinetic and potential energy of the present mesh, and the work
/// of gravity and the viscous dissipation summed over the steps (account).
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_boundaries.hpp"
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"

namespace lagfsi::fluid {

class FluidEnergy {
 public:
  FluidEnergy(const FluidConstants& c, const ParticleCloud& cloud, const FluidMesh& mesh,
              const FluidBoundaries& boundaries)
      : c_(c), cloud_(cloud), mesh_(mesh), boundaries_(boundaries) {}
  /// In one pass over the elements of the current mesh: its area (FluidMesh::area, the same sum); the kinetic
  /// energy with the mesh-lumped masses rho A_e / 3; the potential energy of gravity, -rho integral of g . x dA
  /// (exact on linear triangles: rho A_e g . centroid), zero at the origin. Unlike gravity_work (summed over the
  /// steps with each step's lumped masses) it depends only on the present fluid: KE + PE is the energy balance of
  /// a remeshed flow.
  struct Totals {
    double area = 0, kinetic = 0, potential = 0;
  };
  Totals totals() const;
  /// totals() in a run over MPI processes (mpi_run.hpp): each process sums a share of the elements (PETSc's split of
  /// them, mpi_run::owned_blocks) and the shares are added in rank order, the same bits on every process; totals()
  /// itself with one process. Every process must call it.
  Totals totals_over_processes() const;
  double kinetic() const { return totals().kinetic; }
  double potential() const { return totals().potential; }
  /// Adds the step's gravity work, viscous dissipation (the no-slip walls' "navier" friction included) and
  /// boundary work (before the state is updated): x_new the step's new positions, v the step's velocity (the
  /// scheme's, FluidScheme::step_velocity), t the step's end and dt its length, boundary_force the forces of
  /// the walls and ghosts on the fluid (FluidStep::boundary_force) and constraint_force those of the walls
  /// through their constraints (FluidStep::constraint_force).
  void account(const Vec& x_new, const Vec& v, double t, double dt, const Vec& boundary_force,
               const Vec& constraint_force);
  /// Work of gravity on the fluid and viscous dissipation since the start (summed only when a gravity_work,
  /// viscous_dissipation, total_energy or boundary_work probe exists: enabled()).
  double gravity_work() const { return gravity_work_; }
  double dissipation() const { return dissipation_; }
  /// Work done on the fluid by moving walls and by the structure's ghost particles since the start,
  /// sum over steps of F . dx at the prescribed particles (F the reaction the boundary applies, the mean of
  /// the step's start and end values).
  double boundary_work() const { return boundary_work_; }
  bool enabled() const { return enabled_; }
  void enable() { enabled_ = true; }
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  const FluidConstants& c_;
  const ParticleCloud& cloud_;
  const FluidMesh& mesh_;
  const FluidBoundaries& boundaries_;
  double gravity_work_ = 0, dissipation_ = 0, boundary_work_ = 0;
  Vec boundary_force_prev_;  // the boundary forces at the start of the step
  bool enabled_ = false;     // account() only for runs that probe it
};

}  // namespace lagfsi::fluid
