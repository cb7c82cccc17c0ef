#pragma once
/// @file fluid_boundaries.hpp (private to src/fluid)
/// The fluid's boundary conditions as the schemes see them: one list of boundaries (fluid_boundary.hpp), the walls
/// first (fluid_walls.hpp: their model's implementation), then the case file's "boundaries" in their order, and
/// the step's prescribed components and frictions of them all. A boundary's index in the list is its constraints'
/// and frictions' `boundary`; the walls' constraints come first, in the walls' own order (FluidWalls::constraints),
/// so that a wall's constraint k is entry k here.
#include "fluid_boundary.hpp"
#include "fluid_walls.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace lagfsi::fluid {

class FluidBoundaries {
 public:
  /// The walls: the first boundary (before read).
  void set_walls(std::unique_ptr<FluidWalls> walls);
  FluidWalls& walls() { return *walls_; }
  const FluidWalls& walls() const { return *walls_; }
  /// Reads /bodies/i/boundaries (an array; each entry's "type" picks the builder from the registry).
  void read(Params boundaries, const BoundaryContext& ctx);
  /// Whether the case has boundaries besides the walls.
  bool empty() const { return list_.size() <= 1; }

  // --- The start of a step.

  /// Whether a boundary finds the particles it holds at every step (FluidBoundary::finds_contacts).
  bool finds_contacts() const;
  /// Every boundary finds the particles it holds (FluidBoundary::find).
  void find(const ParticleCloud& cloud, double t);
  /// Per particle (n of them): how many of its components the boundaries found hold (before update).
  std::vector<char> held(Index n) const;
  /// Whether p lies along a boundary (free-surface marking).
  bool along(const Vec2& p) const;
  /// Whether p lies along a part of a boundary that does not move.
  bool along_fixed(const Vec2& p) const;
  /// Every boundary adjusts what it holds to the marked free surface.
  void settle(const std::vector<std::uint8_t>& free);
  /// The step's prescribed components and frictions, every boundary's in turn (a boundary leaves a particle that a
  /// boundary before it holds to that one); called at the start of every step, after find.
  void update(const ParticleCloud& cloud, double t);

  // --- The step's prescribed components.

  const std::vector<BoundaryConstraint>& constraints() const { return all_; }
  double position(const BoundaryConstraint& k, double t) const { return list_[index(k)]->position(k, t); }
  double velocity(const BoundaryConstraint& k, double t) const { return list_[index(k)]->velocity(k, t); }
  /// Per particle (n of them): how many of its components are prescribed (0, 1 or 2).
  std::vector<char> on_wall(Index n) const;
  /// The boundaries' own particles and the prescribed components at their positions at time t (X0: the initial
  /// positions).
  void place(double t, const Vec& X0, Vec& x) const;
  /// The same for the velocities and accelerations.
  void set_motion(double t, Vec& v, Vec& a) const;
  /// The boundaries' own particles' velocities and accelerations at time t (FluidBoundary::move_own).
  void move_own(double t, Vec& v, Vec& a) const {
    for (const auto& b : list_) b->move_own(t, v, a);
  }
  /// The particles' frames (the walls'; particle_frames.hpp).
  const ParticleFrames& frames() const { return walls_ && walls_->frames() ? *walls_->frames() : no_frames_; }

  // --- What the boundaries add to the system.

  /// The step's components sliding against a boundary's friction, and its coefficient and velocity.
  const std::vector<BoundaryFriction>& frictions() const { return frictions_; }
  double friction_coefficient(const BoundaryFriction& f) const { return list_[index(f)]->friction_coefficient(f); }
  double friction_velocity(const BoundaryFriction& f, double t) const {
    return list_[index(f)]->friction_velocity(f, t);
  }
  /// Whether element t carries no viscous stress.
  bool inviscid(const std::array<Index, 3>& t) const;

  // --- After the step.

  /// Every boundary's after_step (force: the step's constraint forces, FluidStep::constraint_force, each boundary
  /// receiving its own); the area they added (inflows).
  double after_step(ParticleCloud& cloud, const Vec& x_start, double t, const FluidMesh& mesh, const Vec& force);

  // --- Open boundaries.

  /// Open boundaries present (an outflow or an inflow).
  bool open() const;
  /// The outflow that takes a fluid particle at x (its index), or -1 (none does).
  int taker(const Vec2& x) const;
  /// The outflow in whose strip x lies (FluidBoundary::in_outlet_strip; its index), or -1.
  int outlet_strip(const Vec2& x) const;
  /// Boundary b took `particles` particles and `area` of the mesh.
  void left(int b, long particles, double area) { list_[static_cast<size_t>(b)]->left(particles, area); }
  /// The particles held by a boundary that keeps their pressure unknown are not free surface (`free`, per
  /// particle); the step's constraints (update) must be current.
  void clear_free_surface(std::vector<std::uint8_t>& free) const;
  /// Per particle: the index among the case's boundaries of the inflow in whose inlet layer it lies
  /// (FluidBoundary::in_inlet: held by it, or by a wall at its ends), or -1.
  std::vector<int> inlets(const ParticleCloud& cloud) const;
  /// Whether x lies in an inflow's inlet layer or within a spacing of an outflow (the open boundaries' faces).
  bool at_open_face(const Vec2& x) const;
  /// The name of the case's boundary j (/bodies/i/boundaries/j).
  const std::string& name(int j) const { return names_[static_cast<size_t>(j)]; }
  /// An outflow's particles on the mesh's boundary (`free`) take p = 0: their pressure components of `fixed` (3 per
  /// particle) are set.
  void fix_outlet_pressure(const ParticleCloud& cloud, const std::vector<std::uint8_t>& free,
                           std::vector<char>& fixed) const;
  /// The triangles the boundaries add to the advected domain.
  std::vector<std::array<Vec2, 3>> fluid_regions() const;
  /// summary.json: each boundary's numbers by its name (the case's boundaries; empty without them).
  Json summary() const;
  /// Checkpoints: the walls' section, then each boundary's.
  void serialize(StateArchive& ar);

 private:
  template <class K>
  static size_t index(const K& k) {
    return static_cast<size_t>(k.boundary);
  }
  FluidWalls* walls_ = nullptr;                       // list_[0]
  std::vector<std::unique_ptr<FluidBoundary>> list_;  // the walls, then the case's boundaries
  std::vector<std::string> names_;                    // the case's boundaries' names (list_[b + 1]'s)
  std::vector<BoundaryConstraint> all_;
  std::vector<BoundaryFriction> frictions_;
  std::vector<size_t> first_;  // per boundary: the index of its first constraint in all_ (and all_.size() last)
  std::vector<BoundaryConstraint> scratch_;
  ParticleFrames no_frames_;
};

}  // namespace lagfsi::fluid
