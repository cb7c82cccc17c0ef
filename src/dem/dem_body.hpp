#pragma once
// What the DEM body's parts work on (src/dem/include/lagfsi/dem/dem_model.hpp): the discs and their dofs, the
// contact law, the walls, the neighbour lists with their per-pair state, the blast, the energy counters.
//
// Dofs: (x, y, theta) per disc, 3 n entries of the KinematicState, inverse masses 1/m, 1/m, 1/I (1/I = 0
// when rotation is off). Time stepping: the shared central difference (time_integrator.hpp,
// explicit_step_into) in sub-steps of the driver's step.
#include <lagfsi/dem/dem_blast.hpp>
#include <lagfsi/dem/dem_contact_law.hpp>
#include <lagfsi/dem/dem_neighbour_grid.hpp>
#include <lagfsi/dem/dem_particles.hpp>
#include <lagfsi/dem/dem_walls.hpp>
#include <lagfsi/time_integrator.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lagfsi::dem {

/// Where and how the crater is measured (dem_output.hpp, crater_profile).
struct CraterSettings {
  bool enabled = false;
  double surface = 0;  ///< initial ground level (0 in the input: the top of the bed at t = 0, after any settling)
  double bin = 0;      ///< bin width (0: 2 d_max)
  double centre = 0;   ///< x of the crater's centre (default: the charge's x)
  std::vector<double> offsets = {-0.05, 0.0, 0.05};  ///< where H1, H2, H3 are read (from the centre)
};

/// Everything a step changes is a plain member, so that a copy of the body is the retry snapshot of
/// DemModel::predict (the discs' order and properties, the dofs, the lists and their histories, the walls'
/// offsets, the blast's exposure, the energy counters); the work counters (substeps, rebuilds, timings) keep
/// counting across a retry.
struct DemBody {
  std::string name;
  std::string file;  // case file (errors)
  Discs discs;
  KinematicState state;  // 3 n dofs
  Vec inv_mass, force;   // 3 n
  // Shared and immutable (the integrator and the law keep no state): a copy of the body is a snapshot of the
  // whole state (DemModel::predict).
  std::shared_ptr<const TimeIntegrator> integrator;
  std::shared_ptr<const ContactLaw> law;
  std::vector<Wall> walls;
  std::vector<std::pair<int, int>> segments;  // (wall, segment) of every wall segment
  Vec2 gravity = Vec2::Zero();
  bool rotation = true;
  double inertia_factor = 0.5;
  double dt = 0, dt_critical = 0;  // sub-step, critical step 2 / omega_max
  long substeps = 0;

  // neighbour search
  NeighbourGrid grid;
  PairList pairs;
  std::vector<double> history;     // tangential spring of each pair
  std::vector<double> pair_force;  // 3 per pair: Fx, Fy on i, -ft (torque per unit radius)
  std::vector<std::uint8_t> pair_rupture;
  std::vector<double> pair_roll;  // rolling-resistance torque on i (on j: minus it), when the law has one
  std::vector<double> x_build;    // 2 per disc: positions at the last build
  std::vector<Vec2> wall_offset_build;
  double skin = 0, r_max = 0, r_min = 0;
  bool reorder = true;
  long rebuilds = 0;
  // wall contacts (CSR by disc): segment index into `segments`, history, force on the disc
  std::vector<Index> wall_row, wall_seg;
  std::vector<double> wall_history, wall_force;  // wall_force: 2 per entry
  std::vector<Index> where;                      // id -> current index

  // energy bookkeeping (only when a probe asks for it)
  bool track_energy = false;
  std::vector<double> pair_elastic, pair_dissipated, disc_elastic, disc_dissipated;
  double elastic = 0, dissipated = 0, blast_work = 0, energy0 = 0;
  // The energy guard (DemModel::solve_iteration), always on: the mechanical energy without the contacts' elastic
  // part, E = kinetic + gravity potential, can exceed its value at t = 0 plus the initial elastic energy
  // (energy_ref) only by the work put in (blast_work, wall_work: the moving walls' work on the discs) in an exact
  // run; a gain above energy_scale (the energy the body can hold or release at t = 0) is an instability.
  double wall_work = 0, energy_ref = 0, energy_scale = 0;
  double initial_overlap = 0;  // largest initial overlap / radius (walls and pairs) accepted by overlap_tolerance

  // blast
  std::optional<Blast> blast;
  std::vector<double> blast_force;  // 2 per disc (current order)

  // what was chosen on purpose or came out unlike asked (summary.json's warnings, stderr)
  std::vector<std::string> warnings;

  bool csv = false;
  CraterSettings crater;  // write <name>_discs.csv with the .vtp

  // settling stage: walls removed at its end
  std::vector<std::string> remove_after_settle;

  // timing
  double t_force = 0, t_rebuild = 0, t_blast = 0;

  size_t size() const { return discs.size(); }
  Vec2 position(Index p) const { return {state.x[3 * p], state.x[3 * p + 1]}; }
  Vec2 velocity(Index p) const { return {state.v[3 * p], state.v[3 * p + 1]}; }

  /// The out-of-balance forces at (x, v, t) into f (contacts, walls, gravity, blast); advances the tangential
  /// histories by v_t h (h = 0: no advance, e.g. at t = 0).
  void compute_forces(const Vec& x, const Vec& v, double t, double h, Vec& f);
  /// Whether the lists must be rebuilt before a step of h (a disc would move more than skin/2, or a disc and
  /// a wall come closer by more than skin, since the last build).
  bool needs_rebuild(double h) const;
  /// Rebuilds the pair and wall lists at the current positions (reordering the discs in cell order first,
  /// when `reorder`); the tangential histories of the contacts that persist are carried over.
  void rebuild();
  /// Moves the walls to time t.
  void place_walls(double t);
  /// Applies the rupture marks of the last force evaluation (Sabatucci law).
  void apply_marks();

  double kinetic_energy() const;
  double rotational_energy() const;
  double gravity_potential() const;  // - sum m g.x
  int contact_count() const;
  double max_contact_force() const;
};

}  // namespace lagfsi::dem
