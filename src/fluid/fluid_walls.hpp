#pragma once
/// @file fluid_walls.hpp (private to src/fluid)
/// The fluid's rigid walls (/bodies/i/walls): their polylines, motions and slip flags, their particles (PFEM
/// mode) or constraints (fixed connectivity), and the check that puts back the fluid particles that crossed
/// one (keep_inside_walls).
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"
#include <lagfsi/fluid/particle_cloud.hpp>
#include "point_grid.hpp"

#include <lagfsi/params.hpp>
#include <lagfsi/time_function.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// A rigid wall: a polyline of particles (PFEM mode) or a line of constraints (fixed-connectivity mode),
/// optionally moving: x(t) = X + value * f(t) (or value * int f for a prescribed velocity).
struct Wall {
  std::string name;
  std::vector<Vec2> polyline;
  bool slip = false;
  Vec2 value = Vec2::Zero();
  std::shared_ptr<TimeFunction> fn;
  bool velocity = false;
  std::vector<Index> particles;  // PFEM mode: its particles in polyline order
  std::vector<int> fluid_side;   // per segment: +1 / -1 the initial fluid lies on the side of
                                 // perp(b - a) / of its opposite, 0 on both or neither (keep_inside_walls)
  Vec2 offset(double t) const {
    if (!fn) return Vec2::Zero();
    return value * (velocity ? fn->integral(t) : fn->value(t));
  }
  /// Prescribed velocity and acceleration (central differences of the offset in time; exact to round-off
  /// for smooth functions, the mean slope across a kink of a table).
  Vec2 velocity_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-6;
    return (offset(t + d) - offset(t - d)) / (2 * d);
  }
  Vec2 acceleration_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-4;
    return (offset(t + d) - 2.0 * offset(t) + offset(t - d)) / (d * d);
  }
};

class FluidWalls {
 public:
  /// Reads the walls of the case (`walls`: /bodies/i/walls); h checks their segments' lengths.
  void read(Params walls, double h, const std::filesystem::path& base_dir);
  bool empty() const { return walls_.empty(); }
  const std::vector<Wall>& all() const { return walls_; }

  /// PFEM mode: the walls' particles, spaced at most h along each polyline (a corner shared with an earlier
  /// wall reuses its particle), appended to pts and kind and added to `grid`; `walls` names the errors.
  void place_particles(const Params& walls, double h, std::vector<Vec2>& pts, std::vector<ParticleKind>& kind,
                       PointGrid& grid);
  /// The polylines' bounding box (lo > hi without walls).
  void bounding_box(Vec2& lo, Vec2& hi) const;
  /// The fluid side of each wall segment from the initial particles (`pts`, of kinds `kind`).
  void set_fluid_sides(const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind);
  /// Fixed-connectivity mode: the particles (at `pts`) on a wall are constrained (both components, or the
  /// normal one on a slip wall); `body` names the errors.
  void constrain_fixed_mesh(const Params& body, const std::vector<Vec2>& pts, double h);
  /// Fixed-connectivity mode: the constrained (particle, component) pairs.
  const std::vector<std::pair<Index, int>>& constraints() const { return slip_; }

  /// Slip walls in PFEM mode: the elements that touch a slip-wall particle carry no viscous stress, so the
  /// wall transmits no shear (the free-slip condition, applied over the first layer of elements); the
  /// normal velocity is still stopped by the wall particles' positions.
  bool inviscid(const std::array<Index, 3>& t) const {
    for (Index i : t)
      if (i < static_cast<Index>(slip_particle_.size()) && slip_particle_[i]) return true;
    return false;
  }
  /// Velocity and acceleration of the moving walls' particles at time t (their prescribed motion).
  void set_wall_motion(double t, Vec& v, Vec& a) const;
  /// The wall particles' prescribed positions at time t into x (X0 their initial positions).
  void place(double t, const Vec& X0, Vec& x) const;
  /// Fluid particles whose step crossed a wall segment go back to its fluid side (PFEM mode; x_start the
  /// positions at the start of the step, t the end of the step).
  void keep_inside_walls(ParticleCloud& cloud, const FluidMesh& mesh, const Vec& x_start, double t);
  /// Fluid particles put back inside a wall so far (keep_inside_walls).
  long crossings() const { return wall_crossings_; }
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  std::vector<Wall> walls_;
  std::vector<char> slip_particle_;          // per wall particle (wall particles come first and are never removed)
  std::vector<std::pair<Index, int>> slip_;  // fixed-connectivity mode: (particle, component) constrained
  long wall_crossings_ = 0;                  // fluid particles put back inside a wall (keep_inside_walls)
};

}  // namespace lagfsi::fluid
