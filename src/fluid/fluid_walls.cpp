// The fluid's rigid walls (fluid_walls.hpp): reading them, their particles or constraints, their prescribed
// motion, and keeping the fluid particles on their fluid side (or putting them on the wall).
#include "fluid_walls.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lagfsi::fluid {

namespace {

const KeyTable kWallKeys("/bodies/*/walls/* (fluid body)",
                         "A rigid wall: a polyline that holds the fluid, fixed or with a prescribed motion.",
                         {{"name", "wall", "Wall name; default: wall<index>.", kDerived},
                          {"points", nullptr, "The polyline [[x, y], ...] (m), at least two distinct points."},
                          {"slip", false, "true: no viscous stress along the wall (free slip); false: no slip."},
                          {"motion", Json::object(),
                           "Prescribed motion (see /bodies/*/walls/*/motion (fluid body)); default {}: fixed."}});

const KeyTable kWallMotionKeys("/bodies/*/walls/*/motion (fluid body)",
                               "A wall's rigid translation: value times a function of time.",
                               {{"type", nullptr,
                                 "prescribed_displacement (m), prescribed_velocity (m/s), or prescribed_rotation "
                                 "(see /bodies/*/walls/*/motion (prescribed_rotation))."},
                                {"value", nullptr, "The displacement or velocity [x, y], scaled by the function."},
                                {"function", nullptr,
                                 "Function of time (see time function (type constant) and others)."}});

const KeyTable kWallRotationKeys(
    "/bodies/*/walls/*/motion (prescribed_rotation)",
    "A wall turned about a pivot (a flap wave maker): the angle theta(t) = value f(t) (rad, counter-clockwise); "
    "the walls must be \"wall_model\": \"particles\".",
    {{"type", "prescribed_rotation", "`prescribed_rotation`."},
     {"pivot", nullptr, "The point [x, y] (m) the wall turns about."},
     {"value", 1.0, "The angle (rad) per unit of the function (-1: clockwise for a positive function)."},
     {"function", nullptr, "Function of time (see time function (type flap_wavemaker) and others)."}});

}  // namespace

void FluidWalls::read(Params walls, double h, const std::filesystem::path& base_dir) {
  for (size_t i = 0; i < walls.size(); ++i) {
    Params w = walls.at(i);
    w.validate(kWallKeys, {{"name", "wall" + std::to_string(i)}});
    Wall wall;
    wall.name = w.string("name");
    wall.polyline = w.points("points");
    if (wall.polyline.size() < 2) w.fail("points", "a wall needs at least two points");
    for (size_t k = 0; k + 1 < wall.polyline.size(); ++k)
      if (!((wall.polyline[k + 1] - wall.polyline[k]).norm() > 1e-6 * h))
        w.fail("points", "segment " + std::to_string(k) + " has zero length (points " + std::to_string(k) + " and " +
                             std::to_string(k + 1) + " coincide)");
    wall.slip = w.boolean("slip");
    Params mo = w.at("motion");
    if (!mo.json().empty()) {
      if (!mo.has("type")) mo.fail("type", "required key is missing");
      const std::string mt =
          mo.choice("type", {"prescribed_displacement", "prescribed_velocity", "prescribed_rotation"});
      if (mt == "prescribed_rotation") {
        if (!turns()) mo.fail("type", "a turning wall needs remeshing (walls of particles or constraints)");
        if (!wall.slip && navier_)
          w.fail("slip", "a turning wall with \"wall_friction\": \"navier\" must be a slip wall");
        mo.validate(kWallRotationKeys);
        wall.rotation = true;
        wall.pivot = mo.vec2("pivot");
        wall.angle = mo.number("value");
        wall.fn = make_time_function(mo.at("function"), base_dir);
        walls_.push_back(std::move(wall));
        continue;
      }
      mo.validate(kWallMotionKeys);
      wall.value = mo.vec2("value");
      wall.fn = make_time_function(mo.at("function"), base_dir);
      wall.velocity = mt == "prescribed_velocity";
    }
    walls_.push_back(std::move(wall));
  }
}

bool FluidWalls::inclined() const {
  for (const auto& w : walls_) {
    if (w.rotation) return true;
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k)
      if (!axis_aligned(w.polyline[k + 1] - w.polyline[k])) return true;
  }
  return false;
}

void FluidWalls::bounding_box(Vec2& lo, Vec2& hi) const {
  lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const auto& w : walls_)
    for (const auto& q : w.polyline) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
}

void FluidWalls::bounding_box_at(double t, Vec2& lo, Vec2& hi) const {
  lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const auto& w : walls_) {
    for (const auto& q : w.polyline) {
      lo = lo.cwiseMin(w.point_at(q, t));
      hi = hi.cwiseMax(w.point_at(q, t));
    }
  }
}

namespace {
// Whether the path from p to q (on a wall) crosses the segment c-d before it reaches q: then that segment stands
// between p and the wall. A parallel segment (a collinear neighbour) is not in the way.
bool path_blocked(const Vec2& p, const Vec2& q, const Vec2& c, const Vec2& d) {
  const Vec2 r = q - p, s = d - c;
  const double den = cross(r, s);
  if (std::abs(den) <= 1e-14 * r.norm() * s.norm()) return false;
  const double t = cross(c - p, s) / den, u = cross(c - p, r) / den;
  return t > 1e-9 && t < 1.0 - 1e-9 && u >= 0.0 && u <= 1.0;
}
}  // namespace

void FluidWalls::set_fluid_sides(const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind) {
  // The fluid side of each wall segment: the side of the initial fluid particles that see it (whose
  // projection falls on it, with no wall segment between; 0 when there are some on both sides, as beside a
  // baffle). A segment that no particle sees, as the downstream face of an obstacle hidden by the obstacle
  // itself, takes the side of its neighbours along the polyline when they agree: the fluid stays on the same
  // side of a wall's walk around a corner. (Counting the particles that face a segment through the obstacle
  // gave that face the upstream side, and particles sliding along the floor into the obstacle's foot went
  // through it: cases/dam_break_obstacle with walls as constraints.)
  std::vector<std::pair<Vec2, Vec2>> segments;  // every wall's, for the visibility test
  for (const auto& w : walls_)
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k) segments.emplace_back(w.polyline[k], w.polyline[k + 1]);
  const Index np = static_cast<Index>(pts.size());
  for (auto& w : walls_) {
    const size_t ns = w.polyline.size() > 1 ? w.polyline.size() - 1 : 0;
    w.fluid_side.assign(ns, 0);
    std::vector<char> seen(ns, 0);
    for (size_t k = 0; k < ns; ++k) {
      const Vec2 a = w.polyline[k], e = w.polyline[k + 1] - a;
      const Vec2 nrm = Vec2(-e.y(), e.x()).normalized();
      bool pos = false, neg = false;  // a particle sees it from that side
      for (Index i = 0; i < np && !(pos && neg); ++i) {
        if (kind[i] != ParticleKind::Fluid) continue;
        const double u = (pts[i] - a).dot(e) / e.squaredNorm(), dist = (pts[i] - a).dot(nrm);
        if (u < 0 || u > 1 || std::abs(dist) <= 1e-9 * e.norm()) continue;  // (a particle on the wall)
        bool& side = dist > 0 ? pos : neg;
        if (side) continue;
        const Vec2 foot = a + u * e;
        side = std::none_of(segments.begin(), segments.end(),
                            [&](const auto& cd) { return path_blocked(pts[i], foot, cd.first, cd.second); });
      }
      w.fluid_side[k] = pos && !neg ? 1 : neg && !pos ? -1 : 0;
      seen[k] = pos || neg;
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t k = 0; k < ns; ++k) {
        if (seen[k] || w.fluid_side[k] != 0) continue;
        const int before = k > 0 ? w.fluid_side[k - 1] : 0, after = k + 1 < ns ? w.fluid_side[k + 1] : 0;
        const int side = before != 0 && after != 0 ? (before == after ? before : 0) : before + after;
        if (side != 0) {
          w.fluid_side[k] = side;
          changed = true;
        }
      }
    }
  }
}

void FluidWalls::add_skew_contacts(const std::vector<Skew>& skew, const Vec& x, double t) {
  // Frames: a particle on inclined segments of one line takes the line's normal. One that is also on a
  // segment of another direction (inclined, or axis-aligned: the constraints found before) is at a corner:
  // held there, both components in the x-y frame (as the axes' constraints hold a corner of a tank).
  const Index np = static_cast<Index>(x.size() / 2);
  std::vector<Vec2>& frames = frames_.normals();
  frames.assign(static_cast<size_t>(np), Vec2::Zero());
  std::vector<char> corner(static_cast<size_t>(np), 0), axis(static_cast<size_t>(np), 0);
  for (const BoundaryConstraint& k : constraints_) axis[static_cast<size_t>(k.i)] = 1;
  for (const Skew& k : skew) {
    const auto i = static_cast<size_t>(k.i);
    Vec2& f = frames[i];
    if (axis[i] || (frames_.rotated(k.i) && std::abs(f.x() * k.n.y() - f.y() * k.n.x()) > 1e-9))
      corner[i] = 1;
    else if (!frames_.rotated(k.i))
      f = k.n;
  }
  const auto at_corner = [&](Index i) { return corner[static_cast<size_t>(i)] != 0; };
  // A corner: the axes' constraints and frictions found there go; it is held in the x-y frame.
  const auto drop_at_corner = [&](auto& list) {
    list.erase(std::remove_if(list.begin(), list.end(), [&](const auto& k) { return at_corner(k.i); }), list.end());
  };
  drop_at_corner(constraints_);
  drop_at_corner(frictions_);
  std::vector<char> done(static_cast<size_t>(np), 0);
  const size_t first = constraints_.size();  // the anchors of a turning wall's constraints, below
  for (const Skew& k : skew) {
    const auto i = static_cast<size_t>(k.i);
    if (done[i]) continue;
    done[i] = 1;
    const Wall& w = walls_[static_cast<size_t>(k.wall)];
    const Vec2 off = w.offset(t), q = x.segment<2>(2 * k.i);
    if (corner[i]) {
      frames[i] = Vec2::Zero();
      constraints_.push_back({k.i, 0, q.x() - off.x(), k.wall, 0});
      constraints_.push_back({k.i, 1, q.y() - off.y(), k.wall, 0});
      continue;
    }
    // The normal constraint of its first segment; a collinear segment found later adds nothing (its line is
    // the same, whichever way its normal faces).
    constraints_.push_back({k.i, 0, k.base, k.wall, k.side});
    if (!w.slip && navier_)
      frictions_.push_back({k.i, 1, k.wall});
    else if (!w.slip)
      constraints_.push_back({k.i, 1, frames_.direction(k.i, 1).dot(q - off), k.wall, 0, true});
  }
  for (size_t c = first; c < constraints_.size(); ++c) {  // a turning wall's: the wall's point under the particle
    BoundaryConstraint& k = constraints_[c];
    const Wall& w = walls_[static_cast<size_t>(k.part)];
    if (w.rotation) k.anchor = w.reference_of(x.segment<2>(2 * k.i), t);
  }
  bool any = false;
  for (Index i = 0; i < np && !any; ++i) any = frames_.rotated(i);
  if (!any) frames.clear();
}

void FluidWalls::place_own(double t, const Vec& X0, Vec& x) const {
  for (const auto& w : walls_)
    for (Index j : w.particles) x.segment<2>(2 * j) = w.point_at(X0.segment<2>(2 * j), t);
}

void FluidWalls::move_own(double t, Vec& v, Vec& a) const {
  for (const auto& w : walls_) {
    if (!w.fn) continue;
    if (w.rotation) {  // each particle's own
      for (size_t k = 0; k < w.particles.size(); ++k) {
        const Index j = w.particles[k];
        v.segment<2>(2 * j) = w.velocity_of(w.particle_X[k], t);
        a.segment<2>(2 * j) = w.acceleration_of(w.particle_X[k], t);
      }
      continue;
    }
    const Vec2 vw = w.velocity_at(t), aw = w.acceleration_at(t);
    for (Index j : w.particles) {
      v.segment<2>(2 * j) = vw;
      a.segment<2>(2 * j) = aw;
    }
  }
}

void FluidWalls::constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                           std::vector<BoundaryConstraint>& out) {
  (void)cloud;
  (void)taken;
  (void)t;
  out.insert(out.end(), constraints_.begin(), constraints_.end());
}

void FluidWalls::count_held(std::vector<char>& held) const {
  for (const auto& k : constraints_)
    if (k.i < static_cast<Index>(held.size())) ++held[static_cast<size_t>(k.i)];
}

bool FluidWalls::along(const Vec2& p) const { return along(p, false); }

bool FluidWalls::along_fixed(const Vec2& p) const { return along(p, true); }

bool FluidWalls::along(const Vec2& p, bool fixed_only) const {
  for (const Wall& w : walls_) {
    if (fixed_only && w.fn) continue;  // a moving wall
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s)
      if (w.distance_at(s, p, contact_t_) <= contact_tol_) return true;
  }
  return false;
}

}  // namespace lagfsi::fluid
