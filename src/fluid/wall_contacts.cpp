// "wall_model": "constraints" (fluid_walls.hpp): the fluid particles on the walls found at every step, the contact
// line let free, the particles a ceiling pulls let go, and the particles that arrive at a wall put on it.
#include "fluid_walls.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::fluid {

void WallContacts::find_contacts(const Vec& x, const std::vector<ParticleKind>& kind, double t) {
  const double h = h_;
  constraints_.clear();
  frictions_.clear();
  frames_.normals().clear();
  const double tol = 1e-6 * h;
  contact_t_ = t;
  contact_tol_ = tol;
  const Index np = static_cast<Index>(kind.size());
  std::vector<Skew> skew;
  for (size_t wi = 0; wi < walls_.size(); ++wi) {
    const Wall& w = walls_[wi];
    const Vec2 off = w.offset(t);
    for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
      const Vec2 a = w.point_at(w.polyline[s], t), b = w.point_at(w.polyline[s + 1], t);
      if (w.rotation || !axis_aligned(b - a)) {  // (a turning wall: in its frame even when upright)
        const Vec2 e = b - a, nrm = w.normal_at(s, t);
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
  std::sort(constraints_.begin(), constraints_.end(), [&](const BoundaryConstraint& p, const BoundaryConstraint& q) {
    return same_dof(p, q) ? p.tangential < q.tangential : by_dof(p, q);
  });
  constraints_.erase(std::unique(constraints_.begin(), constraints_.end(), same_dof), constraints_.end());
  // A friction on a component that another wall constrains (a corner) goes, and so does a second one found
  // at a joint.
  if (frictions_.empty()) return;
  std::sort(frictions_.begin(), frictions_.end(), by_dof);
  frictions_.erase(std::unique(frictions_.begin(), frictions_.end(), same_dof), frictions_.end());
  frictions_.erase(std::remove_if(frictions_.begin(), frictions_.end(),
                                  [&](const BoundaryFriction& f) {
                                    return std::binary_search(constraints_.begin(), constraints_.end(),
                                                              BoundaryConstraint{f.i, f.c, 0.0, 0}, by_dof);
                                  }),
                   frictions_.end());
}

void WallContacts::free_contact_line(const std::vector<std::uint8_t>& free) {
  constraints_.erase(std::remove_if(constraints_.begin(), constraints_.end(),
                                    [&](const BoundaryConstraint& k) {
                                      return k.tangential && k.i < static_cast<Index>(free.size()) && free[k.i];
                                    }),
                     constraints_.end());
}

long WallContacts::release_pulled(ParticleCloud& cloud, const Vec& force) {
  if (static_cast<size_t>(force.size()) != constraints_.size()) return 0;
  const Vec2& gravity = gravity_;
  long released = 0;
  Vec& x = cloud.x();
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const BoundaryConstraint& q = constraints_[k];
    const Vec2 d = frames_.direction(q.i, q.c);
    const double threshold = release_per_area_ * cloud.h(q.i) * cloud.h(q.i);
    if (q.side == 0 || !(q.side * d.dot(gravity) > 0) || !(q.side * force[static_cast<Index>(k)] < -threshold))
      continue;
    x.segment<2>(2 * q.i) += q.side * 1e-3 * cloud.h(q.i) * d;
    ++released;
  }
  wall_releases_ += released;
  return released;
}

void WallContacts::follow_turning_walls(ParticleCloud& cloud, double t) const {
  Vec& x = cloud.x();
  for (const BoundaryConstraint& k : constraints_) {
    const Wall& w = walls_[static_cast<size_t>(k.part)];
    if (!w.rotation || k.c != 0 || !frames_.rotated(k.i) || k.i >= cloud.n()) continue;
    // The wall's line at t through the anchor's new position, with the normal the frame had turned as the wall.
    const Vec2 n1 = w.turn(w.turn_back(frames_.direction(k.i, 0), contact_t_), t), a1 = w.point_at(k.anchor, t);
    x.segment<2>(2 * k.i) -= n1.dot(x.segment<2>(2 * k.i) - a1) * n1;
  }
}

void WallContacts::snap_to_walls(ParticleCloud& cloud, const Vec& x_start, double t) {
  const double snap_fraction = snap_fraction_;
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
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        const Vec2 a = w.point_at(w.polyline[k], t), b = w.point_at(w.polyline[k + 1], t), e = b - a;
        const Vec2 p0 = x_start.segment<2>(2 * i), p1 = x.segment<2>(2 * i);
        Vec2 nrm = w.normal_at(k, t);
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
        // The wall's motion where the particle lands (a turning wall's point there).
        const Vec2 landed = x.segment<2>(2 * i);
        const Vec2 vw = w.rotation ? w.velocity_of(w.reference_of(landed, t), t) : w.velocity_at(t);
        const Vec2 aw = w.rotation ? w.acceleration_of(w.reference_of(landed, t), t) : w.acceleration_at(t);
        // The normal velocity and acceleration become the wall's (no-slip walls held by constraints: the whole
        // velocity, as the constraints of the next step will hold them; with "navier" friction it slides).
        Vec2 v = vel.segment<2>(2 * i), acc = cloud.a().segment<2>(2 * i);
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

}  // namespace lagfsi::fluid
