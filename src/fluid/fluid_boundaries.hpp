#pragma once
/// @file fluid_boundaries.hpp (private to src/fluid)
/// The fluid's boundary conditions as the schemes see them: the walls (fluid_walls.hpp) and the boundaries of the
/// case file's "boundaries" (fluid_boundary.hpp), with one list of the step's prescribed components. The walls'
/// come first, in the walls' own order (FluidWalls::constraints), so that a wall's constraint k is entry k here;
/// each entry's `boundary` says whose it is (0: the walls; b > 0: the case's boundary b - 1).
#include "fluid_boundary.hpp"
#include "fluid_walls.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace lagfsi::fluid {

class FluidBoundaries {
 public:
  explicit FluidBoundaries(FluidWalls& walls) : walls_(walls) {}
  /// Reads /bodies/i/boundaries (an array; each entry's "type" picks the builder from the registry).
  void read(Params boundaries, const BoundaryContext& ctx);
  bool empty() const { return boundaries_.empty(); }

  /// The step's prescribed components, from the walls' current constraints and every boundary's (a boundary
  /// leaves a particle on a wall to the wall); called at the start of every step, after the walls found theirs.
  void update(const ParticleCloud& cloud, double t);
  const std::vector<WallConstraint>& constraints() const { return all_; }
  double position(const WallConstraint& k, double t) const;
  double velocity(const WallConstraint& k, double t) const;
  /// Per particle (n of them): how many of its components are prescribed (0, 1 or 2).
  std::vector<char> on_wall(Index n) const;
  /// The walls' prescribed positions at time t into x (FluidWalls::place), then the boundaries' components.
  void place(double t, const Vec& X0, Vec& x) const;
  /// The walls' prescribed velocities and accelerations at time t (FluidWalls::set_wall_motion), then the
  /// boundaries' components.
  void set_motion(double t, Vec& v, Vec& a) const;
  /// Every boundary's after_step; the area they added (inflows).
  double after_step(ParticleCloud& cloud, const Vec& x_start, double t);
  /// Open boundaries present (an outflow or an inflow).
  bool open() const;
  /// The outflow that takes a fluid particle at x (its index), or -1 (none does).
  int taker(const Vec2& x) const;
  /// Boundary b took `particles` particles and `area` of the mesh.
  void left(int b, long particles, double area) { boundaries_[static_cast<size_t>(b)]->left(particles, area); }
  /// The particles held by a boundary that keeps their pressure unknown are not free surface (`free`, per
  /// particle); the step's constraints (update) must be current.
  void clear_free_surface(std::vector<std::uint8_t>& free) const;
  /// An outflow's particles on the mesh's boundary (`free`) take p = 0: their pressure components of `fixed` (3 per
  /// particle) are set.
  void fix_outlet_pressure(const ParticleCloud& cloud, const std::vector<std::uint8_t>& free,
                           std::vector<char>& fixed) const;
  /// The triangles the boundaries add to the advected domain.
  std::vector<std::array<Vec2, 3>> fluid_regions() const;
  /// summary.json: each boundary's numbers by its name (empty without boundaries).
  Json summary() const;
  void serialize(StateArchive& ar);

 private:
  FluidWalls& walls_;
  std::vector<std::unique_ptr<FluidBoundary>> boundaries_;
  std::vector<std::string> names_;
  std::vector<WallConstraint> all_;
  std::vector<BoundaryConstraint> scratch_;
};

}  // namespace lagfsi::fluid
