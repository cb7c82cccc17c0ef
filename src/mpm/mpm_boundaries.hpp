#pragma once
// Conditions on the grid of an MPM body and loads on its particles (mpm_boundaries.cpp): fixed components,
// prescribed motion (velocity, or an accelerogram integrated to the nodes' velocity), viscous absorbing
// boundaries (Lysmer & Kuhlemeyer 1969), free-field boundaries (Zienkiewicz, Bicanic & Shen 1989), and
// particle forces. Each is read from the body's case-file keys ("boundary_conditions", "absorbing_boundaries",
// "loads") and applied to the grid arrays by the schemes.
#include <lagfsi/mpm/mpm_material.hpp>
#include <lagfsi/mpm/mpm_state.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/time_function.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <vector>

namespace lagfsi::mpm {

/// A fixed component of a grid node.
struct FixedComponent {
  Index node;
  int comp;
};

/// Grid node components that move with a prescribed velocity: value * f(t), or value * int_0^t f for a
/// prescribed acceleration f (a base accelerogram).
struct PrescribedMotion {
  Index node;
  int comp;
  double value;
  std::shared_ptr<TimeFunction> fn;
  bool acceleration;
  double velocity(double t) const { return value * (acceleration ? fn->integral(t) : fn->value(t)); }
};

/// Viscous absorbing boundary (Lysmer & Kuhlemeyer 1969): dashpots rho c_p on the normal and rho c_s on the
/// tangential velocity of the selected grid nodes, each over a boundary length of one cell.
struct Dashpot {
  Index node;
  Vec2 normal;
  double length;  // tributary boundary length: h/2 per neighbouring selected node along the boundary
};

/// Free-field boundary (Zienkiewicz, Bicanic & Shen 1989, "Earthquake input definition and the transmitting
/// boundary conditions"; as in FLAC and Plaxis): beside a lateral boundary a 1D soil column of the body's
/// elastic material (per unit width, nodes at the boundary's grid nodes) is shaken by the same base motion
/// and computed alongside; each boundary node gets the dashpots on its velocity relative to the column's
/// and the column's stress as a traction, t = sigma_ff n (n outward), sigma_ff = the static stress plus
/// the column's dynamic stress. The static part is the geostatic K0 sigma_v (start = 0) or, with a start
/// time, the reactions of rollers that hold the boundary until then (the procedure of FLAC: a static stage
/// on rollers, then the free field with the rollers' forces; needed when the structure's weight loads the
/// boundary beyond the far field's geostatic stress). A column of a uniform layer moves as the 1D site
/// response, so the boundary neither reflects the outgoing waves nor disturbs the incoming ones.
struct FreeField {
  std::vector<Index> nodes;    // boundary grid nodes from the base up (the column's nodes)
  std::vector<double> length;  // tributary boundary length of each node
  std::vector<double> le;      // column element lengths (node k to k+1; the last may stop at the top)
  std::vector<double> mass;    // column node masses per unit width
  std::vector<double> sv;      // geostatic vertical stress at the nodes (negative below the top)
  std::vector<Vec2> u, v;      // column displacements and velocities (dynamic part)
  std::array<const PrescribedMotion*, 2> base{nullptr, nullptr};  // base motion per component
  std::array<bool, 2> base_fixed{false, false};
  Vec2 normal;                   // outward (+-1, 0)
  double start = 0;              // rollers (fixed x) before this time, then the free field
  std::vector<double> reaction;  // the rollers' last horizontal reactions (the static traction after start)
  bool active(double t) const { return t >= start; }
  /// Dynamic strains of element k (shear gamma_xy, axial eps_yy) plus beta times their rates: the strain
  /// that a stiffness-proportional (Kelvin-Voigt) damping beta adds to the elastic stress.
  Vec2 strain(size_t k, double beta) const { return (u[k + 1] - u[k] + beta * (v[k + 1] - v[k])) / le[k]; }
};

/// Particle forces (total force split over the selected particles) scaled by a function of time.
struct ParticleLoad {
  std::vector<Index> particles;
  Vec2 force;
  std::shared_ptr<TimeFunction> fn;
};

/// The conditions on the grid nodes of one body.
struct GridBoundaries {
  std::vector<FixedComponent> fixed;  // grid node, component
  std::vector<PrescribedMotion> moving;
  std::vector<Dashpot> dashpots;
  std::vector<FreeField> free_fields;
  double k0 = 0;  // the K0 of the geostatic initial stress (free-field columns)

  /// Zeroes the fixed components of a nodal array.
  void apply_fixed(std::vector<Vec2>& vec) const {
    for (const auto& [node, comp] : fixed) vec[node][comp] = 0.0;
  }
  /// Prescribed motion after the grid update: the node's velocity at t1 = t + dt; its force is what that takes.
  void impose_motion(Grid& grid, double t1, double dt) const;
  /// Advances the free-field columns by dt (their base moves with the grid's base at t + dt).
  void step_free_fields(double t, double dt, const MpmMaterial& mat, double damp_mass, double damp_stiff);
  /// Adds the free-field columns' stresses as tractions on their boundary nodes' grid forces.
  void add_free_field_tractions(Grid& grid, double t, const MpmMaterial& mat, double damp_stiff) const;
  /// Adds the dashpot forces of the absorbing and free-field boundaries (implicit in the node's velocity).
  void add_dashpot_forces(Grid& grid, double t, double dt, const MpmMaterial& mat);
};

/// Adds the particle loads at time t to grid forces f.
void add_particle_loads(const std::vector<ParticleLoad>& loads, const std::vector<Support>& support, double t,
                        std::vector<Vec2>& f);

// ---------------------------------------------------------------- reading the case file

/// "loads": particle forces on the particles whose reference position the selection picks.
std::vector<ParticleLoad> read_particle_loads(Params loads, const std::vector<Vec2>& reference_positions,
                                              const std::filesystem::path& base_dir);
/// "boundary_conditions": fixed components and prescribed motion of the selected grid nodes.
void read_boundary_conditions(Params bcs, const std::vector<Vec2>& nodes, bool two_phase,
                              const std::filesystem::path& base_dir, GridBoundaries& out);
/// What the absorbing and free-field boundaries need of the body.
struct BoundaryBody {
  const Grid& grid;
  const Particles& particles;
  int particles_per_cell;
  double density;
  double gravity_y;  // 0 for a body without gravity
  bool two_phase;
};
/// "absorbing_boundaries": dashpots, or free-field columns (free_field: true); after the boundary conditions
/// (a column's base takes the motion of its base node).
void read_absorbing_boundaries(Params ab, const std::vector<Vec2>& nodes, const BoundaryBody& body,
                               GridBoundaries& out);

}  // namespace lagfsi::mpm
