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
                               {{"type", nullptr, "prescribed_displacement (m) or prescribed_velocity (m/s)."},
                                {"value", nullptr, "The displacement or velocity [x, y], scaled by the function."},
                                {"function", nullptr,
                                 "Function of time (see time function (type constant) and others)."}});

}  // namespace

void FluidWalls::read(Params walls, double h, const std::filesystem::path& base_dir, bool constraints) {
  constraint_model_ = constraints;
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
      const std::string mt = mo.choice("type", {"prescribed_displacement", "prescribed_velocity"});
      mo.validate(kWallMotionKeys);
      wall.value = mo.vec2("value");
      wall.fn = make_time_function(mo.at("function"), base_dir);
      wall.velocity = mt == "prescribed_velocity";
    }
    walls_.push_back(std::move(wall));
  }
}

namespace {
bool axis_aligned(const Vec2& d) { return std::abs(d.x()) <= 1e-12 * d.norm() || std::abs(d.y()) <= 1e-12 * d.norm(); }
}  // namespace

bool FluidWalls::inclined() const {
  for (const auto& w : walls_)
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k)
      if (!axis_aligned(w.polyline[k + 1] - w.polyline[k])) return true;
  return false;
}

void FluidWalls::place_particles(const Params& walls, double h, std::vector<Vec2>& pts, std::vector<ParticleKind>& kind,
                                 PointGrid& grid) {
  double wall_particles = 0;
  for (const auto& w : walls_)
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s) wall_particles += (w.polyline[s + 1] - w.polyline[s]).norm() / h;
  if (!(wall_particles <= 1e6)) walls.fail("more than a million wall particles at this spacing");
  for (auto& w : walls_) {
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
      const Vec2 a = w.polyline[s], c = w.polyline[s + 1];
      const int n = std::max(1, static_cast<int>(std::ceil((c - a).norm() / h * (1 - 1e-12))));
      for (int k = (s == 0 ? 0 : 1); k <= n; ++k) {
        const Vec2 p = a + (c - a) * (double(k) / n);
        // Shared corner with an earlier wall: reuse its particle.
        const Index found = grid.find(p, 1e-9 * h, pts);
        if (found < 0) {
          w.particles.push_back(static_cast<Index>(pts.size()));
          grid.add(p, static_cast<Index>(pts.size()));
          pts.push_back(p);
          kind.push_back(ParticleKind::Wall);
          slip_particle_.push_back(w.slip);
        } else {
          w.particles.push_back(found);
          slip_particle_[found] = slip_particle_[found] || w.slip;
        }
      }
    }
  }
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
    const Vec2 off = w.offset(t);
    for (const auto& q : w.polyline) {
      lo = lo.cwiseMin(q + off);
      hi = hi.cwiseMax(q + off);
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

void FluidWalls::constrain_fixed_mesh(const Params& body, const std::vector<Vec2>& pts, double h, bool frames) {
  // Fixed connectivity: the initial mesh for the whole run; walls constrain the fluid nodes on them (a node on an
  // inclined slip segment in the segment's frame, as find_contacts does).
  const Index np = static_cast<Index>(pts.size());
  contact_t_ = 0;
  contact_tol_ = 1e-6 * h;
  std::vector<Skew> skew;
  for (size_t wi = 0; wi < walls_.size(); ++wi) {
    const Wall& w = walls_[wi];
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
      const Vec2 a = w.polyline[s], d = w.polyline[s + 1] - a;
      const bool horizontal = std::abs(d.y()) < 1e-12 * d.norm(), vertical = std::abs(d.x()) < 1e-12 * d.norm();
      const bool inclined_slip = w.slip && !horizontal && !vertical;
      if (inclined_slip && !frames)
        body.fail("walls",
                  "inclined slip walls need the monolithic scheme (the fractional step constrains the x and "
                  "y components)");
      const Vec2 nrm = w.fluid_normal(s);
      const bool sided = s < w.fluid_side.size() && w.fluid_side[s] != 0;
      const Vec2 off = w.offset(0.0);
      for (Index i = 0; i < np; ++i) {
        if (w.distance(s, pts[i], Vec2::Zero()) > 1e-6 * h) continue;
        const int wall = static_cast<int>(wi);
        if (inclined_slip) {
          skew.push_back({i, nrm, nrm.dot(pts[i] - off), wall, sided ? 1 : 0});
          continue;
        }
        if (!w.slip || horizontal) constraints_.push_back({i, 1, pts[i].y() - off.y(), wall});
        if (!w.slip || vertical) constraints_.push_back({i, 0, pts[i].x() - off.x(), wall});
      }
    }
  }
  if (skew.empty()) return;
  Vec x(2 * np);
  for (Index i = 0; i < np; ++i) x.segment<2>(2 * i) = pts[static_cast<size_t>(i)];
  add_skew_contacts(skew, x, 0.0);
}

void FluidWalls::set_wall_motion(double t, Vec& v, Vec& a) const {
  for (const auto& w : walls_) {
    if (!w.fn) continue;
    const Vec2 vw = w.velocity_at(t), aw = w.acceleration_at(t);
    for (Index j : w.particles) {
      v.segment<2>(2 * j) = vw;
      a.segment<2>(2 * j) = aw;
    }
  }
  // The constrained components, also on fixed walls (zero): a particle put on a wall by snap_to_walls
  // arrives with its own velocity, which the constraint's first step would otherwise reflect (the
  // trapezoidal rule's v_{n+1} = 2 (x_{n+1} - x_n) / dt - v_n).
  for (const auto& k : constraints_) {
    const Wall& w = walls_[static_cast<size_t>(k.wall)];
    set_component(v, k.i, k.c, along(w.velocity_at(t), k.i, k.c));
    set_component(a, k.i, k.c, along(w.acceleration_at(t), k.i, k.c));
  }
}

void FluidWalls::place(double t, const Vec& X0, Vec& x) const {
  for (const auto& w : walls_)
    for (Index j : w.particles) x.segment<2>(2 * j) = X0.segment<2>(2 * j) + w.offset(t);
  for (const auto& k : constraints_) set_component(x, k.i, k.c, constraint_position(k, t));
}

void FluidWalls::find_contacts(const Vec& x, const std::vector<ParticleKind>& kind, double t, double h) {
  if (!constraint_model_) return;
  constraints_.clear();
  frictions_.clear();
  frames_.clear();
  const double tol = 1e-6 * h;
  contact_t_ = t;
  contact_tol_ = tol;
  const Index np = static_cast<Index>(kind.size());
  std::vector<Skew> skew;
  for (size_t wi = 0; wi < walls_.size(); ++wi) {
    const Wall& w = walls_[wi];
    const Vec2 off = w.offset(t);
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
      const Vec2 a = w.polyline[s] + off, b = w.polyline[s + 1] + off;
      if (!axis_aligned(b - a)) {
        const Vec2 e = b - a, nrm = w.fluid_normal(s);
        const bool sided = s < w.fluid_side.size() && w.fluid_side[s] != 0;
        const double len = e.norm();
        for (Index i = 0; i < np; ++i) {
          if (kind[i] != ParticleKind::Fluid) continue;
          const Vec2 q = x.segment<2>(2 * i);
          const double u = (q - a).dot(e) / len;
          if (std::abs(nrm.dot(q - a)) > tol || u < -tol || u > len + tol) continue;
          skew.push_back({i, nrm, nrm.dot(a - off), static_cast<int>(wi), sided ? 1 : 0});
        }
        continue;
      }
      const int n = std::abs(b.y() - a.y()) < std::abs(b.x() - a.x()) ? 1 : 0;  // the normal component
      const int m = 1 - n;
      // The fluid side along n: the fluid side of the segment is that of perp(b - a) = (-(b - a).y, (b - a).x)
      // times fluid_side.
      const Vec2 e = b - a;
      const double perp_n = n == 0 ? -e.y() : e.x();
      const int side = s < w.fluid_side.size() && w.fluid_side[s] != 0 ? (perp_n * w.fluid_side[s] > 0 ? 1 : -1) : 0;
      const double lo = std::min(a[m], b[m]) - tol, hi = std::max(a[m], b[m]) + tol;
      for (Index i = 0; i < np; ++i) {
        if (kind[i] != ParticleKind::Fluid) continue;
        const Vec2 q = x.segment<2>(2 * i);
        if (std::abs(q[n] - a[n]) > tol || q[m] < lo || q[m] > hi) continue;
        const int wall = static_cast<int>(wi);
        constraints_.push_back({i, n, a[n] - off[n], wall, side});
        if (!w.slip && navier_)
          frictions_.push_back({i, m, wall});  // slides against the wall's friction
        else if (!w.slip)
          constraints_.push_back({i, m, q[m] - off[m], wall, 0, true});  // held where it is
      }
    }
  }
  if (!skew.empty()) add_skew_contacts(skew, x, t);
  // A particle at a joint of two collinear segments (or of two walls) is found twice: one constraint per
  // component, a wall's normal one rather than another wall's tangential one (free_contact_line drops those).
  const auto by_dof = [](const auto& p, const auto& q) { return p.i != q.i ? p.i < q.i : p.c < q.c; };
  const auto same_dof = [](const auto& p, const auto& q) { return p.i == q.i && p.c == q.c; };
  std::sort(constraints_.begin(), constraints_.end(), [&](const WallConstraint& p, const WallConstraint& q) {
    return same_dof(p, q) ? p.tangential < q.tangential : by_dof(p, q);
  });
  constraints_.erase(std::unique(constraints_.begin(), constraints_.end(), same_dof), constraints_.end());
  // A friction on a component that another wall constrains (a corner) goes, and so does a second one found
  // at a joint.
  if (frictions_.empty()) return;
  std::sort(frictions_.begin(), frictions_.end(), by_dof);
  frictions_.erase(std::unique(frictions_.begin(), frictions_.end(), same_dof), frictions_.end());
  frictions_.erase(std::remove_if(frictions_.begin(), frictions_.end(),
                                  [&](const WallFriction& f) {
                                    return std::binary_search(constraints_.begin(), constraints_.end(),
                                                              WallConstraint{f.i, f.c, 0.0, 0}, by_dof);
                                  }),
                   frictions_.end());
}

void FluidWalls::add_skew_contacts(const std::vector<Skew>& skew, const Vec& x, double t) {
  // Frames: a particle on inclined segments of one line takes the line's normal. One that is also on a
  // segment of another direction (inclined, or axis-aligned: the constraints found before) is at a corner:
  // held there, both components in the x-y frame (as the axes' constraints hold a corner of a tank).
  const Index np = static_cast<Index>(x.size() / 2);
  frames_.assign(static_cast<size_t>(np), Vec2::Zero());
  std::vector<char> corner(static_cast<size_t>(np), 0), axis(static_cast<size_t>(np), 0);
  for (const WallConstraint& k : constraints_) axis[static_cast<size_t>(k.i)] = 1;
  for (const Skew& k : skew) {
    const auto i = static_cast<size_t>(k.i);
    Vec2& f = frames_[i];
    if (axis[i] || (rotated(k.i) && std::abs(f.x() * k.n.y() - f.y() * k.n.x()) > 1e-9))
      corner[i] = 1;
    else if (!rotated(k.i))
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
  for (const Skew& k : skew) {
    const auto i = static_cast<size_t>(k.i);
    if (done[i]) continue;
    done[i] = 1;
    const Wall& w = walls_[static_cast<size_t>(k.wall)];
    const Vec2 off = w.offset(t), q = x.segment<2>(2 * k.i);
    if (corner[i]) {
      frames_[i] = Vec2::Zero();
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
      constraints_.push_back({k.i, 1, direction(k.i, 1).dot(q - off), k.wall, 0, true});
  }
  bool any = false;
  for (Index i = 0; i < np && !any; ++i) any = rotated(i);
  if (!any) frames_.clear();
}

void FluidWalls::free_contact_line(const std::vector<std::uint8_t>& free) {
  constraints_.erase(std::remove_if(constraints_.begin(), constraints_.end(),
                                    [&](const WallConstraint& k) {
                                      return k.tangential && k.i < static_cast<Index>(free.size()) && free[k.i];
                                    }),
                     constraints_.end());
}

long FluidWalls::release_pulled(ParticleCloud& cloud, const Vec& force, const Vec2& gravity, double threshold) {
  if (!constraint_model_ || static_cast<size_t>(force.size()) != constraints_.size()) return 0;
  long released = 0;
  Vec& x = cloud.x();
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const WallConstraint& q = constraints_[k];
    const Vec2 d = direction(q.i, q.c);
    if (q.side == 0 || !(q.side * d.dot(gravity) > 0) || !(q.side * force[static_cast<Index>(k)] < -threshold))
      continue;
    x.segment<2>(2 * q.i) += q.side * 1e-3 * cloud.h(q.i) * d;
    ++released;
  }
  wall_releases_ += released;
  return released;
}

bool FluidWalls::on_a_segment(const Vec2& p) const {
  for (const Wall& w : walls_) {
    const Vec2 off = w.offset(contact_t_);
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s)
      if (w.distance(s, p, off) <= contact_tol_) return true;
  }
  return false;
}

std::vector<char> FluidWalls::on_wall(Index n) const {
  std::vector<char> flag(static_cast<size_t>(n), 0);
  for (const auto& k : constraints_)
    if (k.i < n) ++flag[static_cast<size_t>(k.i)];
  return flag;
}

void FluidWalls::snap_to_walls(ParticleCloud& cloud, const Vec& x_start, double t, double snap_fraction) {
  // Walls without particles: a fluid particle is held off a wall only by the constraints of the particles on
  // it, so one that arrives (an impact, a film reaching a wall) is put on the wall and constrained from the
  // next step on. Beyond a segment (within its span, having started less than h beyond it) or within
  // snap_fraction h of it and closer than at the start of the step: its normal coordinate becomes the
  // wall's, and so do its normal velocity and acceleration (an inelastic impact).
  const std::vector<ParticleKind>& kind = cloud.kind();
  Vec& x = cloud.x();
  Vec& vel = cloud.v();
  for (Index i = 0; i < cloud.n(); ++i) {
    if (kind[i] != ParticleKind::Fluid) continue;
    const double h = cloud.h(i);
    for (const auto& w : walls_) {
      const Vec2 off = w.offset(t), vw = w.velocity_at(t);
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        const Vec2 a = w.polyline[k] + off, b = w.polyline[k + 1] + off, e = b - a;
        const Vec2 p0 = x_start.segment<2>(2 * i), p1 = x.segment<2>(2 * i);
        Vec2 nrm = w.fluid_normal(k);
        // Within the segment's span, or (beyond it) within half a spacing past one of its ends: a particle
        // leaving through a corner is past both segments' ends (it lands on the end, the corner).
        const double u = (p1 - a).dot(e) / e.squaredNorm(), slack = 1e-6 * h / e.norm(), reach = 0.5 * h / e.norm();
        if (!(u >= -reach && u <= 1 + reach)) continue;
        const bool in_span = u >= -slack && u <= 1 + slack;
        if (w.fluid_side[k] == 0 && nrm.dot(p0 - a) < 0) {
          nrm = -nrm;  // a wall with fluid on both sides: towards the side the particle came from
        }
        const double d1 = nrm.dot(p1 - a), d0 = nrm.dot(p0 - a);
        if (std::abs(d1) <= 1e-6 * h) continue;  // on it already
        const bool beyond = d1 < 0 && d0 > -h, near = in_span && d1 > 0 && d1 < snap_fraction * h && d1 < d0;
        if (!beyond && !near) continue;
        x.segment<2>(2 * i) = in_span ? Vec2(p1 - d1 * nrm) : Vec2(u < 0 ? a : b);
        // The normal velocity and acceleration become the wall's (no-slip walls held by constraints: the whole
        // velocity, as the constraints of the next step will hold them; with "navier" friction it slides).
        Vec2 v = vel.segment<2>(2 * i), acc = cloud.a().segment<2>(2 * i);
        const Vec2 aw = w.acceleration_at(t);
        if (w.slip || navier_) {
          v -= (v - vw).dot(nrm) * nrm;
          acc -= (acc - aw).dot(nrm) * nrm;
        } else {
          v = vw;
          acc = aw;
        }
        vel.segment<2>(2 * i) = v;
        cloud.a().segment<2>(2 * i) = acc;
        ++(beyond ? wall_crossings_ : wall_snaps_);
      }
    }
  }
}

void FluidWalls::keep_inside_walls(ParticleCloud& cloud, const FluidMesh& mesh, const Vec& x_start, double t) {
  // A fluid particle in no element with a wall's particles (a drop flying ballistically) is not held by
  // the wall, and a fast one may pass between the particles of its element: in one step it can cross the
  // wall (a drop at 4 m/s moves 0.8 h a step at h = 5 mm, dt = 1 ms). Without this check the drops were
  // lost through the walls and dropped at the domain box (1.3 % of the fluid in elastic_obstacle_walhorn by
  // 1 s). A particle that ends more than 0.5 h (h if held, below) beyond a wall segment is put back 0.05 h
  // on the segment's fluid side, and loses the velocity component into the wall (an inelastic impact), if
  //  - the segment has a fluid side (the initial fluid's) and the particle started less than that
  //    beyond it (within the segment's span), or
  //  - its path x_n -> x_{n+1} crossed the segment (the side it came from is then the fluid side).
  // A particle in an element with a wall particle is held by the mesh, and its excursions across the wall
  // line of up to one spacing (a film sliding on the floor between the no-slip particles) are the
  // discretization's: only a held particle more than h beyond the wall is put back (putting back the film's
  // particles at 0.25 h made the film at a dam-break toe run ahead: dam_break_floor front RMS 0.21 -> 0.50;
  // 0.5 h leaves that film alone).
  const std::vector<ParticleKind>& kind = cloud.kind();
  const std::vector<char> held =
      mesh.in_element_with(cloud.n(), [&](Index i) { return kind[i] == ParticleKind::Wall; });
  Vec& x = cloud.x();
  Vec& vel = cloud.v();
  for (Index i = 0; i < cloud.n(); ++i) {
    if (kind[i] != ParticleKind::Fluid) continue;
    const Vec2 p0 = x_start.segment<2>(2 * i);
    Vec2 p1 = x.segment<2>(2 * i);
    const double tol = (held[i] ? 1.0 : 0.5) * cloud.h(i);
    for (const auto& w : walls_) {
      const Vec2 off = w.offset(t);
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        const Vec2 a = w.polyline[k] + off, b = w.polyline[k + 1] + off, e = b - a;
        Vec2 nrm = w.fluid_normal(k);
        double u;  // where the particle goes back, along the segment
        if (w.fluid_side[k] != 0) {
          u = (p1 - a).dot(e) / e.squaredNorm();
          // Past an end of the segment by less than tol, at a corner whose other segment the particle is
          // beyond as well (the outer quadrant of a tank's corner): a film sliding along the floor a little
          // below it would otherwise leave through the corner, in neither segment's span (dam_break_tank with
          // the level-set detection lost particles there). Put back at the corner.
          const double reach = tol / e.norm();
          const bool past_end = (u < 0 && u >= -reach && k > 0 && w.beyond_line(k - 1, p1, off)) ||
                                (u > 1 && u <= 1 + reach && k + 2 < w.polyline.size() && w.beyond_line(k + 1, p1, off));
          if (!((u >= 0 && u <= 1) || past_end) || nrm.dot(p1 - a) >= -tol || nrm.dot(p0 - a) <= -tol) continue;
          u = std::clamp(u, 0.0, 1.0);
        } else {
          const Vec2 d = p1 - p0;
          const double den = cross(d, e);
          if (std::abs(den) <= 1e-300) continue;  // parallel
          const double s = cross(a - p0, e) / den;
          u = cross(a - p0, d) / den;
          if (!(s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0)) continue;
          if (nrm.dot(p0 - a) < 0) nrm = -nrm;  // towards the side the particle came from
          if (nrm.dot(p1 - a) > -tol) continue;
        }
        p1 = a + u * e + 0.05 * cloud.h(i) * nrm;
        Vec2 v = vel.segment<2>(2 * i);
        const double vn = v.dot(nrm);
        if (vn < 0) v -= vn * nrm;
        vel.segment<2>(2 * i) = v;
        ++wall_crossings_;
      }
    }
    x.segment<2>(2 * i) = p1;
  }
}

}  // namespace lagfsi::fluid
