#pragma once
/// @file fluid_walls.hpp (private to src/fluid)
/// The fluid's rigid walls (/bodies/i/walls): their polylines, motions and slip flags, and how they hold the
/// fluid, one boundary implementation (fluid_boundary.hpp) per wall model:
///  - WallParticles, PFEM mode, "wall_model": "particles" (the classic PFEM; Idelsohn, Oñate & Del Pin 2004): a
///    line of fixed wall particles, spaced h, that the Delaunay mesh connects to the fluid; the fluid particles
///    that crossed one are put back (keep_inside_walls);
///  - WallContacts, PFEM mode, "wall_model": "constraints": no wall particles; the fluid particles lying on a wall
///    carry its condition as constraints (the normal component on a slip wall; on a no-slip one the tangential
///    component too, "wall_friction": "held", or a friction force instead, "navier", below), found again at
///    every step (find_contacts). On a horizontal or vertical segment the components are x and y; a particle
///    on an inclined segment takes the segment's frame (n, t) instead (particle_frames.hpp: its unknowns are
///    rotated, u = n u_n + t u_t, and u_n is the constrained one; Zienkiewicz & Taylor's skew boundary
///    conditions), and a particle where an inclined segment meets a segment of another direction is held at the
///    corner (both components). A particle whose step ends on or beyond a wall, or within snap_fraction h of it
///    while approaching, is put on it (snap_to_walls), and a wall that pulls a particle lets it go
///    (release_pulled). The wall-particle layer is a numerical friction in gentle flows (fluid sliding past a
///    zero-velocity wall particle has a discrete divergence that the continuity equation resists:
///    cases/studies/conservation); nodes on the wall with a normal constraint slide freely, as in a fixed mesh;
///  - FixedMeshWalls, fixed connectivity: the mesh's nodes on a wall are constrained once (constrain_fixed_mesh).
///
/// No-slip walls as constraints, "wall_friction": "navier" (the monolithic scheme's default; "held" the fractional
/// step's): holding the tangential component of every fluid particle on the wall holds a layer of fluid one spacing
/// thick (h) in place, where the real boundary layer is far thinner (sqrt(nu t) = 0.45 mm for water after 0.2 s,
/// against h = 2.9 mm in cases/dam_break_floor): the column's water stays on the wall (its height error at the wall was
/// 0.13 of the column against 0.013 with wall particles and the alpha shape) and the dam break in a tank loses 10 % of
/// its energy before the impact. Instead the particle slides with the Navier condition (Navier 1823): the wall's shear
/// stress is mu (v_t - v_wall,t) / l, with the slip length l = s h
/// ("slip_length" s, 0.5 by default: the particle's velocity is taken as the fluid's at half a spacing from
/// the wall, a modelling choice); over the particle's share of the wall, h, the force on it is
///   F_t = -(mu / s) (v_t - v_wall,t),
/// independent of h. Its dissipation (mu / s) |v_t - v_wall,t|^2 joins the viscous dissipation. The
/// monolithic scheme adds it to its momentum rows, the fractional step to its viscous predictor (implicitly).
#include "fluid_boundary.hpp"
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"
#include "particle_frames.hpp"
#include "point_grid.hpp"

#include <lagfsi/fluid/particle_cloud.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/time_function.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// Whether a segment of direction d is horizontal or vertical.
inline bool axis_aligned(const Vec2& d) {
  return std::abs(d.x()) <= 1e-12 * d.norm() || std::abs(d.y()) <= 1e-12 * d.norm();
}

/// A rigid wall: a polyline of particles (PFEM mode) or a line of constraints (fixed-connectivity mode),
/// optionally moving: translated, x(t) = X + value * f(t) (or value * int f for a prescribed velocity), or turned
/// about a pivot c, x(t) = c + R(theta(t)) (X - c) with theta = angle * f(t) (a flap; remeshed walls only).
struct Wall {
  std::string name;
  std::vector<Vec2> polyline;
  bool slip = false;
  Vec2 value = Vec2::Zero();
  std::shared_ptr<TimeFunction> fn;
  bool velocity = false;
  bool rotation = false;  // turned about `pivot` by angle * f(t) (rad, counter-clockwise)
  Vec2 pivot = Vec2::Zero();
  double angle = 0;
  std::vector<Index> particles;  // PFEM mode: its particles in polyline order
  std::vector<Vec2> particle_X;  // and their initial positions
  std::vector<int> fluid_side;   // per segment: +1 / -1 the initial fluid lies on the side of
                                 // perp(b - a) / of its opposite, 0 on both or neither (keep_inside_walls)
  Vec2 offset(double t) const {
    if (!fn || rotation) return Vec2::Zero();
    return value * (velocity ? fn->integral(t) : fn->value(t));
  }
  /// A vector of the wall turned as the wall is at time t, and back (unchanged unless it rotates).
  Vec2 turn(const Vec2& v, double t) const { return rotation && fn ? rotated(v, angle * fn->value(t)) : v; }
  Vec2 turn_back(const Vec2& v, double t) const { return rotation && fn ? rotated(v, -angle * fn->value(t)) : v; }
  /// v turned by th (rad, counter-clockwise).
  static Vec2 rotated(const Vec2& v, double th) {
    const double c = std::cos(th), s = std::sin(th);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
  }
  /// The wall's point (in its initial position) that is at p at time t.
  Vec2 reference_of(const Vec2& p, double t) const {
    return rotation ? Vec2(pivot + turn_back(p - pivot, t)) : Vec2(p - offset(t));
  }
  /// The distance from p to segment k at time t.
  double distance_at(size_t k, const Vec2& p, double t) const {
    const Vec2 a = point_at(polyline[k], t), e = turn(polyline[k + 1] - polyline[k], t);
    const double u = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (p - (a + u * e)).norm();
  }
  /// Where the wall's point X (in its initial position) is at time t.
  Vec2 point_at(const Vec2& X, double t) const {
    return rotation ? Vec2(pivot + turn(X - pivot, t)) : Vec2(X + offset(t));
  }
  /// The velocity and acceleration of the wall's point X at time t (central differences in time).
  Vec2 velocity_of(const Vec2& X, double t) const {
    if (!rotation) return velocity_at(t);
    const double d = 1e-6;
    return (point_at(X, t + d) - point_at(X, t - d)) / (2 * d);
  }
  Vec2 acceleration_of(const Vec2& X, double t) const {
    if (!rotation) return acceleration_at(t);
    const double d = 1e-4;
    return (point_at(X, t + d) - 2.0 * point_at(X, t) + point_at(X, t - d)) / (d * d);
  }
  /// The unit normal of segment k towards its fluid side (fluid_normal) at time t.
  Vec2 normal_at(size_t k, double t) const { return turn(fluid_normal(k), t); }
  /// Prescribed velocity and acceleration (central differences of the offset in time; exact to round-off
  /// for smooth functions, the mean slope across a kink of a table).
  Vec2 velocity_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-6;
    return (offset(t + d) - offset(t - d)) / (2 * d);
  }
  /// The unit normal of segment k, towards its fluid side when it has one (perp(b - a) otherwise).
  Vec2 fluid_normal(size_t k) const {
    const Vec2 e = polyline[k + 1] - polyline[k];
    const Vec2 n = Vec2(-e.y(), e.x()).normalized();
    return k < fluid_side.size() && fluid_side[k] != 0 ? Vec2(fluid_side[k] * n) : n;
  }
  /// The distance from p to segment k, the wall offset by `off`.
  double distance(size_t k, const Vec2& p, const Vec2& off) const {
    const Vec2 a = polyline[k] + off, e = polyline[k + 1] - polyline[k];
    const double u = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (p - (a + u * e)).norm();
  }
  /// Whether p lies strictly beyond the line of segment k at time t, on the side away from its fluid (false for a
  /// segment with fluid on both sides or none).
  bool beyond_line(size_t k, const Vec2& p, double t) const {
    if (k >= fluid_side.size() || fluid_side[k] == 0) return false;
    const Vec2 a = point_at(polyline[k], t), e = turn(polyline[k + 1] - polyline[k], t);
    return fluid_side[k] * (e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x())) < 0;
  }
  Vec2 acceleration_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-4;
    return (offset(t + d) - 2.0 * offset(t) + offset(t - d)) / (d * d);
  }
};

/// The walls as one boundary: their polylines and motions, the components of the fluid particles they hold
/// (constraints: d . x_i = base + d . the wall's offset(t), d the direction of component c in the particle's frame,
/// particle_frames.hpp; `part` is the wall's index), and those that slide against the Navier friction. The wall
/// models below say which particles they hold and what they do after a step.
class FluidWalls : public FluidBoundary {
 public:
  /// Reads the walls of the case (`walls`: /bodies/i/walls); h checks their segments' lengths.
  void read(Params walls, double h, const std::filesystem::path& base_dir);
  /// "particles", "constraints" or "constraints (fixed connectivity)" (summary.json).
  virtual const char* model() const = 0;
  /// Whether its walls may turn ("prescribed_rotation"): only wall particles follow a turning wall.
  virtual bool turns() const { return false; }
  /// Whether a wall has a segment that is neither horizontal nor vertical, or turns.
  bool inclined() const;
  /// "wall_friction": "navier": the fluid particles on no-slip walls slide against the friction k (v_t - v_wall,t),
  /// k = mu / s (s the slip length in spacings); off: they are held.
  void set_navier_friction(double mu, double slip_length) {
    navier_ = true;
    friction_k_ = mu / slip_length;
  }
  bool navier() const { return navier_; }
  bool empty() const { return walls_.empty(); }
  const std::vector<Wall>& all() const { return walls_; }
  /// The polylines' bounding box (lo > hi without walls); at time t, where their motions have taken them.
  void bounding_box(Vec2& lo, Vec2& hi) const;
  void bounding_box_at(double t, Vec2& lo, Vec2& hi) const;
  /// Whether a wall has a prescribed motion.
  bool moving() const {
    for (const auto& w : walls_)
      if (w.fn) return true;
    return false;
  }
  /// The fluid side of each wall segment from the initial particles (`pts`, of kinds `kind`).
  void set_fluid_sides(const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind);
  /// The constrained components of fluid particles on walls (constrain_fixed_mesh, or the step's contacts).
  const std::vector<BoundaryConstraint>& constraints() const { return constraints_; }
  /// Fluid particles put back inside a wall so far (keep_inside_walls, snap_to_walls from beyond a wall), put on
  /// a wall from its fluid side (snap_to_walls) and let go by a wall pulling them (release_pulled).
  long crossings() const { return wall_crossings_; }
  long snaps() const { return wall_snaps_; }
  long releases() const { return wall_releases_; }

  // FluidBoundary: the constrained components of the particles on walls (in their frames), the walls' particles'
  // motion, the frictions of "navier".
  void count_held(std::vector<char>& held) const override;
  bool along(const Vec2& p) const override;
  bool along_fixed(const Vec2& p) const override;
  void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                 std::vector<BoundaryConstraint>& out) override;
  /// A component on a turning wall follows the wall's point under the particle when it was found (its anchor).
  double position(const BoundaryConstraint& k, double t) const override {
    const Wall& w = walls_[static_cast<size_t>(k.part)];
    if (w.rotation) return frames_.along(w.point_at(k.anchor, t), k.i, k.c);
    return k.base + frames_.along(w.offset(t), k.i, k.c);
  }
  double velocity(const BoundaryConstraint& k, double t) const override {
    const Wall& w = walls_[static_cast<size_t>(k.part)];
    return frames_.along(w.rotation ? w.velocity_of(k.anchor, t) : w.velocity_at(t), k.i, k.c);
  }
  double acceleration(const BoundaryConstraint& k, double t) const override {
    const Wall& w = walls_[static_cast<size_t>(k.part)];
    return frames_.along(w.rotation ? w.acceleration_of(k.anchor, t) : w.acceleration_at(t), k.i, k.c);
  }
  void place_own(double t, const Vec& X0, Vec& x) const override;
  void move_own(double t, Vec& v, Vec& a) const override;
  const ParticleFrames* frames() const override { return &frames_; }
  void frictions(std::vector<BoundaryFriction>& out) const override {
    out.insert(out.end(), frictions_.begin(), frictions_.end());
  }
  double friction_coefficient(const BoundaryFriction& f) const override {
    (void)f;
    return friction_k_;
  }
  double friction_velocity(const BoundaryFriction& f, double t) const override {
    return frames_.along(walls_[static_cast<size_t>(f.part)].velocity_at(t), f.i, f.c);
  }
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar) override;

 protected:
  /// A fluid particle on an inclined segment: the segment's unit normal (towards its fluid side when it has
  /// one), the line n . x = base (without the wall's offset), the wall and whether it has a fluid side.
  struct Skew {
    Index i;
    Vec2 n;
    double base;
    int wall, side;
  };
  /// The frames, corners, constraints and frictions of the particles on inclined segments.
  void add_skew_contacts(const std::vector<Skew>& skew, const Vec& x, double t);
  /// Whether p lies along a wall (within the last contacts' tolerance), of the walls that do not move if fixed_only.
  bool along(const Vec2& p, bool fixed_only) const;

  std::vector<Wall> walls_;
  std::vector<BoundaryConstraint> constraints_;  // fixed connectivity's, or the step's contacts
  std::vector<BoundaryFriction> frictions_;      // the step's particles on no-slip walls, "navier" friction
  ParticleFrames frames_;                        // the step's particles on inclined walls: their walls' normals
  bool navier_ = false;                          // "wall_friction": "navier"
  double friction_k_ = 0;                        // mu / slip_length
  double contact_t_ = 0, contact_tol_ = 0;       // the time and tolerance of the last contacts (along)
  long wall_crossings_ = 0;                      // fluid particles put back inside a wall
  long wall_snaps_ = 0;                          // fluid particles put on a wall from its fluid side
  long wall_releases_ = 0;                       // fluid particles let go by a wall pulling them
};

/// "wall_model": "particles": a line of fixed particles along each wall that the Delaunay mesh connects to the
/// fluid (wall_particles.cpp).
class WallParticles final : public FluidWalls {
 public:
  const char* model() const override { return "particles"; }
  bool turns() const override { return true; }
  /// The walls' particles, spaced at most h along each polyline (a corner shared with an earlier wall reuses its
  /// particle), appended to pts and kind and added to `grid`; `walls` names the errors.
  void place_particles(const Params& walls, double h, std::vector<Vec2>& pts, std::vector<ParticleKind>& kind,
                       PointGrid& grid);
  /// Slip walls: the elements that touch a slip-wall particle carry no viscous stress, so the wall transmits no
  /// shear (the free-slip condition, applied over the first layer of elements); the normal velocity is still
  /// stopped by the wall particles' positions.
  bool inviscid(const std::array<Index, 3>& t) const override {
    for (Index i : t)
      if (i < static_cast<Index>(slip_particle_.size()) && slip_particle_[i]) return true;
    return false;
  }
  /// Fluid particles whose step took them into a wall's solid go back to its fluid side (x_start the positions at
  /// the start of the step, t the end of the step).
  void keep_inside_walls(ParticleCloud& cloud, const FluidMesh& mesh, const Vec& x_start, double t);
  double after_step(const StepEnd& s) override {
    keep_inside_walls(s.cloud, s.mesh, s.x_start, s.t);
    return 0.0;
  }

  /// Where a point lies against the solid behind the sided wall segments at time t: its depth in it (the distance
  /// to the segments' nearest point, negative on the fluid side; -inf without sided segments), that point and the
  /// unit normal towards the fluid there (at a vertex the mean of the normals of the segments meeting there).
  struct SolidDepth {
    double depth = -std::numeric_limits<double>::infinity();
    bool inside = false;
    Vec2 foot = Vec2::Zero(), normal = Vec2::Zero();
  };
  SolidDepth solid_depth(const Vec2& p, double t) const;

 private:
  std::vector<char> slip_particle_;  // per wall particle (wall particles come first and are never removed)
};

/// "wall_model": "constraints": no wall particles; the fluid particles found on a wall at every step carry its
/// condition as constraints (wall_contacts.cpp).
class WallContacts final : public FluidWalls {
 public:
  /// h: the spacing (the contacts' tolerance); snap_fraction: see snap_to_walls; a ceiling lets particle i go when
  /// it pulls it with more than release_per_area h_i^2 against gravity `g` (release_pulled).
  WallContacts(double h, double snap_fraction, const Vec2& g, double release_per_area)
      : h_(h), snap_fraction_(snap_fraction), gravity_(g), release_per_area_(release_per_area) {}
  const char* model() const override { return "constraints"; }
  bool turns() const override { return true; }
  /// The fluid particles (positions x at time t, of kinds `kind`) that lie on a wall segment (within 1e-6 h of
  /// it) become the step's constraints (and, on no-slip walls with "navier" friction, the step's frictions).
  void find_contacts(const Vec& x, const std::vector<ParticleKind>& kind, double t);
  /// A free-surface particle (`free`) on a no-slip wall is held in the normal direction only: the contact line
  /// moves (held, it would pin the water's edge where it first touched).
  void free_contact_line(const std::vector<std::uint8_t>& free);
  /// A particle that a ceiling pulls instead of pushing (force[k], the force of constraint k on the fluid, below
  /// -release_per_area h_i^2 along its fluid side, on a wall whose fluid side faces along gravity: water hanging from a
  /// ceiling or an overhang) is let go: moved 1e-3 h off the wall, it is no longer found on it and falls
  /// (snap_to_walls puts it back if it comes back). Only ceilings: on floors and side walls the reaction's sign
  /// flickers at the contact line and under a moving wall (releasing there took 8 % of the dam break's energy
  /// before the impact and lost 58 % of the shaken tank's water). Returns how many were let go.
  long release_pulled(ParticleCloud& cloud, const Vec& force);
  /// A fluid particle whose step (from x_start) ends beyond a wall segment, or within snap_fraction h of it while
  /// approaching it, is put on the segment and loses its velocity into the wall relative to the wall's (an
  /// inelastic impact); it is constrained from the next step on.
  void snap_to_walls(ParticleCloud& cloud, const Vec& x_start, double t);

  bool finds_contacts() const override { return true; }
  void find(const ParticleCloud& cloud, double t) override { find_contacts(cloud.x(), cloud.kind(), t); }
  void settle(const std::vector<std::uint8_t>& free) override { free_contact_line(free); }
  /// The particles held on a turning wall end the step on the line of the step's frame through their anchor's
  /// new position, which is the wall's own line only where they did not slide along it (they are off it by the
  /// slide times the turn): they are put back on the wall's line at time t, as they are found again.
  void follow_turning_walls(ParticleCloud& cloud, double t) const;
  double after_step(const StepEnd& s) override {
    follow_turning_walls(s.cloud, s.t);
    release_pulled(s.cloud, s.force);
    snap_to_walls(s.cloud, s.x_start, s.t);
    return 0.0;
  }

 private:
  double h_, snap_fraction_;
  Vec2 gravity_;
  double release_per_area_;
};

/// Fixed connectivity: the mesh's nodes on a wall are constrained once, for the whole run (fixed_mesh_walls.cpp).
class FixedMeshWalls final : public FluidWalls {
 public:
  const char* model() const override { return "constraints (fixed connectivity)"; }
  /// The particles (at `pts`) on a wall are constrained (both components, or the normal one on a slip wall: in
  /// the wall's frame on an inclined one, which needs a scheme that solves in frames, `frames`); `body` names the
  /// errors.
  void constrain_fixed_mesh(const Params& body, const std::vector<Vec2>& pts, double h, bool frames);
};

}  // namespace lagfsi::fluid
