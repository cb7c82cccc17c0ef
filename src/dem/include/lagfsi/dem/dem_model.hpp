#pragma once
/// @file dem/dem_model.hpp
/// The Discrete Element Method body ("type": "dem"): 2D discs of unit depth (Cundall & Strack 1979) with
/// contact laws, rigid polyline walls, gravity and an optional air-blast load, after Sabatucci et
/// al. (CILAMCE 2013; shared/spec/004_dem.md).
///
/// The module (public headers in src/dem/include/lagfsi/dem, the rest in src/dem), one concern per file:
///  - discs and their generators (hex lattice, random pack, lists)    dem_particles.hpp, dem_particles.cpp
///  - contact laws: linear spring-dashpot, Hertz-Mindlin, Sabatucci   dem_contact_law.hpp, dem_contact_law.cpp
///  - neighbour search on a cell grid (half Verlet list, skin)        dem_neighbour_grid.hpp, dem_neighbour_grid.cpp
///  - rigid polyline walls                                            dem_walls.hpp, dem_walls.cpp
///  - the air-blast load with shadowing                               dem_blast.hpp, dem_blast.cpp
///  - what the parts work on (discs, dofs, lists, counters)           src/dem/dem_body.hpp
///  - the force sweep and the list maintenance                        dem_forces.cpp
///  - reading the body from the case                                  dem_input.cpp
///  - ParaView output, crater profile                                 dem_output.cpp
///  - probes                                                          dem_probes.cpp
///  - the PhysicsModel lifecycle                                      dem_model.cpp
///  - checkpoints (output.checkpoint, lagfsi run --restart)           dem_checkpoint.cpp
///
/// Time: the shared explicit central difference (time_integrator.hpp, explicit_step_into: velocity Verlet,
/// the damping and the tangential history take the half-step velocity), dofs (x, y, theta) per disc with
/// inverse masses 1/m, 1/m, 1/I. The driver's step is split into n equal sub-steps no longer than the body's
/// "time_step.dt" (default: "fraction" x the critical step); the critical step is 2/omega_max with omega_max
/// = sqrt(k/m) of the stiffest contact of the lightest discs (ContactLaw::max_frequency); a dt above it is
/// refused unless "allow_above_critical" is true, and then a warning (stderr, summary.json).
///
/// Guards: a disc whose centre crosses a wall segment in a sub-step has been pushed through the wall; at the end of
/// every step, kinetic + gravity potential energy may exceed the initial total (with the initial overlaps'
/// elastic energy) only by the blast's and the moving walls' work, give or take the energy the body holds or can
/// release at t = 0: either is a SolverError naming the cause.
#include <lagfsi/case.hpp>
#include <lagfsi/explicit_model.hpp>
#include <lagfsi/model.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

namespace dem {

struct DemBody;
class DemWriter;

class DemModel final : public ExplicitModel {
 public:
  /// Reads the body and builds its discs, law, walls and lists; throws InputError for a bad body.
  DemModel(Params body, const CaseContext& ctx);
  ~DemModel() override;

  std::string name() const override;
  std::string type() const override { return "dem"; }
  Index num_nodes() const override;     ///< the discs
  Index num_elements() const override;  ///< the contacts
  void initialize() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;
  Json summary() const override;
  /// A step above the critical one, initial overlaps above the default tolerance, a random pack looser than asked.
  std::vector<std::string> warnings() const override;
  bool can_checkpoint() const override { return true; }
  /// The whole state after finalize_step (dem_checkpoint.cpp): the discs in their current order with their
  /// properties, marks, dofs and forces; the pair and wall lists as built (pairs, incidences, tangential
  /// histories, reference positions of the skin test), so that the next rebuild and every force sum come when
  /// and as they would have; the walls' offsets; the blast's exposure; the energy sums; the counters and timings;
  /// the output series.
  void serialize(StateArchive& ar) override;

  const DemBody& body() const { return *body_; }
  DemBody& body() { return *body_; }
  /// Advances by one sub-step of length h (rebuilding the lists first when needed).
  void substep(double h);
  /// Total energy now minus the initial one and the blast work (0 for an exact, conservative run; the
  /// dissipated energy counted).
  double energy_balance() const;

 protected:
  /// The step's start: a copy of the DemBody; a retry restores it but keeps the work counters and timings of
  /// the failed attempt (ExplicitModel).
  void save_step_start() override;
  void restore_step_start() override;
  /// The driver's step in sub-steps no longer than the body's dt, then the finite-state and energy checks.
  int advance(double t_new, double dt) override;

 private:
  /// Sets the energy guard's reference and scale at t = 0 (DemBody::energy_ref, energy_scale).
  void start_energy_guard();
  /// Throws SolverError naming the first disc whose position or velocity is not finite.
  void check_finite() const;
  /// Throws SolverError when the energy grew past the work put in.
  void check_energy() const;

  CaseContext ctx_;
  std::unique_ptr<DemBody> body_;
  std::unique_ptr<DemWriter> writer_;
  std::unique_ptr<DemBody> snapshot_;  // the body at the start of the open step (save_step_start)
  double settle_time_ = 0;
  /// A disc near a wall (or fast enough to reach one outside its list: all_walls) and its centre before a
  /// sub-step (DemModel::substep).
  struct NearWall {
    Index disc;
    Vec2 centre;
    bool all_walls;
  };
  std::vector<NearWall> near_wall_;
};

/// Reads a DEM body into `b` (dem_input.cpp). Returns the settling time (0: none).
double read_dem_body(Params body, const CaseContext& ctx, DemBody& b);

}  // namespace dem

/// The DEM body's builder (registered as "dem" in model_registry() of the app layer, model_registry.hpp).
std::unique_ptr<PhysicsModel> make_dem_model(Params body, const CaseContext& ctx);

}  // namespace lagfsi
