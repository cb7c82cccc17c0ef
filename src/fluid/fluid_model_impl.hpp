#pragma once
/// @file fluid_model_impl.hpp (private to src/fluid; the public side is src/fluid/include/lagfsi/fluid/fluid_model.hpp)
/// The PFEM fluid model: a short lifecycle (fluid_model.cpp) over the pieces that own the state: the
/// particles (particle_cloud.hpp), the step's mesh (fluid_mesh.hpp), the walls (fluid_walls.hpp), the ghost
/// particles of a coupled structure (ghosts.hpp), the remeshing (remesh_pipeline.hpp), the volume
/// correction (volume_correction.hpp), the energies (fluid_energy.hpp) and the scheme that solves a step
/// (fluid_scheme.hpp: monolithic_pspg in pspg_scheme.cpp, fractional_step in fractional_step.cpp). The case
/// is read by fluid_input.cpp, the probes are in fluid_probes.cpp.
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_boundaries.hpp"
#include "fluid_common.hpp"
#include "fluid_energy.hpp"
#include "fluid_mesh.hpp"
#include "fluid_scheme.hpp"
#include "fluid_walls.hpp"
#include "ghosts.hpp"
#include "remesh_pipeline.hpp"
#include "volume_correction.hpp"

#include <lagfsi/case.hpp>
#include <lagfsi/fluid/fluid_model.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/vtk_output.hpp>

#include <memory>

namespace lagfsi::fluid {

struct FluidDefaults;  // the defaults that follow from other keys (fluid_defaults.hpp)

class FluidModel final : public PhysicsModel, public InterfaceFluid {
 public:
  FluidModel(Params body, const CaseContext& ctx);
  std::string name() const override { return c_.name; }
  std::string type() const override { return "fluid"; }
  Index num_nodes() const override { return cloud_.n(); }
  Index num_elements() const override { return mesh_.num_elements(); }
  Index num_particles() const override { return cloud_.n(); }
  /// log.csv: the fluid area right after the step's remeshing (fluid_area_remeshed) and at the step's end
  /// (fluid_area), and what the remeshing changed: its area and the kinetic energy of the same velocities
  /// on the new mesh, minus those of the last step's mesh (remesh_dA, remesh_dKE).
  std::vector<Metric> step_metrics() const override {
    return {{"fluid_area_remeshed", volume_.area_remeshed()},
            {"fluid_area", volume_.area_end()},
            {"remesh_dA", remesh_.area_change()},
            {"remesh_dKE", remesh_.kinetic_energy_change()}};
  }
  /// The fluid area (initial mesh, now, of the fluid dropped outside the domain box, and the drift without
  /// the latter: the scheme's own), the particles put back inside a wall (keep_inside_walls), the particle
  /// counts and what remeshing changed over the run (RemeshPipeline::summary).
  Json summary() const override;
  StepLimit stable_step(double courant) const override;

  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  void finalize_step() override;
  void write_output(double t) override;
  /// Over several MPI processes each writes its piece of the fluid's series (fluid_model.cpp).
  bool writes_pieces() const override;
  /// This process's piece of the output of `whole` (the whole fluid on `mesh`).
  void write_piece(double t, const TriMesh& mesh, const VtuData& whole);
  std::unique_ptr<Probe> make_probe(Params p) override;
  bool can_checkpoint() const override { return true; }
  void serialize(StateArchive& ar) override;  // fluid_checkpoint.cpp

  // InterfaceFluid (interface.hpp): ghost particles of a structure's wet boundary (ghosts.hpp).
  int add_ghosts(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent) override;
  bool in_contact() const override { return ghosts_.in_contact(); }
  void set_ghost_motion(const Vec& x, const Vec& v, const Vec& a) override;
  void restart_step() override { start_iterations(); }
  Vec ghost_forces() const override { return ghosts_.forces(); }

  // Read access for probes.
  Index n() const { return cloud_.n(); }
  Vec2 pos(Index i) const { return cloud_.pos(i); }
  Vec2 vel(Index i) const { return cloud_.vel(i); }
  double pressure(Index i) const { return cloud_.p()[i]; }
  bool is_fluid(Index i) const { return cloud_.is_fluid(i); }
  bool is_connected(Index i) const { return mesh_.connected[i] != 0; }
  double spacing() const { return c_.h; }
  /// The walls' polylines' bounding box (lo > hi without walls).
  void walls_box(Vec2& lo, Vec2& hi) const { boundaries_.walls().bounding_box(lo, hi); }
  /// The index of the wall named `name` (FluidWalls::all), or -1.
  int wall_index(const std::string& name) const;
  /// The force (N per m of thickness) the fluid applied to wall `wall` in the last step: minus the reactions of
  /// its constraints ("wall_model": "constraints", FluidStep::constraint_force, in the particles' frames on
  /// inclined segments) plus the Navier friction of the particles sliding on it, or minus the forces its wall
  /// particles applied to the fluid (FluidStep::boundary_force; a corner particle shared by two walls counts for
  /// the first). Zero before the first step.
  Vec2 wall_force(int wall) const;
  /// Where and how hard the fluid pressed on the walls in the last step, particle by particle: each particle held
  /// by a wall (a fluid particle on one, "wall_model": "constraints", or a wall particle) and the force (N per m of
  /// thickness) it passed to the walls, as wall_force takes it (reactions and Navier friction, or minus the wall
  /// particle's force on the fluid) but summed over the walls that hold it. Empty before the first step.
  struct WallLoad {
    Vec2 at, force;
  };
  std::vector<WallLoad> wall_loads() const;
  /// The unit normal, towards the fluid, of the wall segment nearest to p as the walls are at the end of the last
  /// step, and that distance (infinite without walls).
  Vec2 wall_normal_near(const Vec2& p, double& distance) const;
  /// A wall_force probe needs the boundary forces of the step (the schemes compute them on demand).
  void request_boundary_forces() { step_.energy = true; }
  const std::vector<std::array<Index, 3>>& triangles() const { return mesh_.tri; }
  double kinetic_energy() const { return energy_.kinetic(); }
  /// Potential energy of gravity over the current mesh (FluidEnergy::potential).
  double potential_energy() const { return energy_.potential(); }
  /// Work of gravity on the fluid and viscous dissipation since the start (FluidEnergy::account; summed only
  /// when a gravity_work or viscous_dissipation probe exists).
  double gravity_work() const { return energy_.gravity_work(); }
  double viscous_dissipation() const { return energy_.dissipation(); }
  /// Potential energy put into the fluid by the "surface" volume correction's moves, -sum m_i g . dx_i.
  double correction_energy() const { return volume_.correction_energy(); }
  double area_end() const { return volume_.area_end(); }
  double water_area() const { return volume_.water_area(); }
  /// Work done on the fluid by moving walls and by the structure's ghost particles (FluidEnergy::boundary_work).
  double boundary_work() const { return energy_.boundary_work(); }
  /// The energy balance: KE + PE + viscous dissipation - boundary work. Constant for an exact discretization;
  /// its drift is the numerical energy (remeshing, time integration).
  double total_energy() const {
    const FluidEnergy::Totals t = energy_.totals();
    return t.kinetic + t.potential + energy_.dissipation() - energy_.boundary_work();
  }

 private:
  /// Walls as constraints: visit(i, part, force) for each force a wall (FluidWalls::all()[part]) took from fluid
  /// particle i in the last step: each constrained component's reaction and each Navier friction, sign flipped.
  template <class Visit>
  void each_constraint_load(const Visit& visit) const;
  /// The body's own keys (fluid_input.cpp): its constants, the domain detection's settings into rs and how the
  /// walls hold the fluid; d the defaults that follow from other keys (fluid_defaults).
  void read_body_keys(Params b, const FluidDefaults& d, RemeshPipeline::Settings& rs);
  /// /bodies/i/scheme: the scheme's settings (ps or fs), the volume correction and the particle management's
  /// settings into rs; returns whether it is the monolithic scheme.
  bool read_scheme(Params s, const FluidDefaults& d, RemeshPipeline::Settings& rs, PspgSettings& ps,
                   FractionalStepSettings& fs);
  /// The particles' initial velocities and pressures (initial_velocity, initial_pressure, initial_state).
  void set_initial_state(Params b, const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind);
  /// The particles, the walls and the initial state from the case (fluid_input.cpp).
  void build_particles(Params b);
  /// Dirichlet flags of the step (step_.fixed): wall positions, slip constraints, free-surface and
  /// unconnected pressures, and the pressure level of incompressible water that no boundary sets
  /// (pressure_level.hpp; an inflow into such water is an InputError at its boundary).
  void set_dirichlet(double t_start);
  /// The boundaries find the particles they hold at time t; where they hold those they find on them (walls as
  /// constraints), the free surface is marked again (a held particle is not free surface) and they settle on it.
  void hold(double t);
  /// The step's first iterate (after remeshing, or again when a coupling re-solves the step): pressures
  /// of the last step, positions moved with the last velocities, walls and ghosts at their prescribed places.
  void start_iterations();
  FluidParts parts() { return {c_, cloud_, mesh_, boundaries_, ghosts_, volume_, step_, times_}; }

  FluidConstants c_;
  CaseContext ctx_;
  ParticleCloud cloud_;
  FluidMesh mesh_;
  FluidBoundaries boundaries_;  // the walls and the case's other boundaries (fluid_boundaries.hpp)
  Params boundaries_input_;     // /bodies/i/boundaries (the errors found at a step name its entries)
  Ghosts ghosts_;
  VolumeCorrection volume_{c_, cloud_, mesh_};
  RemeshPipeline remesh_{c_, cloud_, mesh_, ghosts_};
  FluidEnergy energy_{c_, cloud_, mesh_, boundaries_};
  FluidStep step_;
  std::unique_ptr<FluidScheme> scheme_;

  Index n_initial_ = 0;            // particles at the start (summary.json)
  bool fractional_ = false;        // the scheme is the fractional step (read_scheme)
  bool wall_constraints_ = false;  // "wall_model": "constraints" (read by the constructor for build_particles)
  bool solved_once_ = false;
  bool step_open_ = false;    // predict called and the step not finalized yet (a retry if predicted again)
  bool step_meshed_ = false;  // the open step's remesh completed (a retry keeps that mesh)
  std::unique_ptr<PvdSeries> series_, wall_series_;
};

}  // namespace lagfsi::fluid
