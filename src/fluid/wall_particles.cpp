// "wall_model": "particles" (fluid_walls.hpp): placing the walls' particles, and putting back the fluid particles
// whose step crossed a wall.
#include "fluid_walls.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lagfsi::fluid {

void WallParticles::place_particles(const Params& walls, double h, std::vector<Vec2>& pts,
                                    std::vector<ParticleKind>& kind, PointGrid& grid) {
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
        w.particle_X.push_back(found < 0 ? p : pts[static_cast<size_t>(found)]);
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

WallParticles::SolidDepth WallParticles::solid_depth(const Vec2& p, double t) const {
  // The nearest point of the sided segments. Where it is a vertex that several segments share (a corner, also
  // between two walls), the segment whose line p is furthest from decides the side (a point is inside a polygon
  // iff it is inside the edge, of those meeting at its nearest vertex, whose line it is furthest from); where it
  // is the free end of a wall (one segment), p is beyond the wall's span, in the open.
  SolidDepth best;
  double best_d2 = std::numeric_limits<double>::infinity(), best_line = -1;
  bool at_end = false;
  int reached = 0;  // the segments whose nearest point is best.foot
  Vec2 normal_sum = Vec2::Zero();
  for (const auto& w : walls_) {
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
      if (w.fluid_side[k] == 0) continue;
      const Vec2 a = w.point_at(w.polyline[k], t), e = w.point_at(w.polyline[k + 1], t) - a;
      const Vec2 nrm = w.normal_at(k, t);
      const double u = (p - a).dot(e) / e.squaredNorm();
      const Vec2 foot = a + std::clamp(u, 0.0, 1.0) * e;
      const double d2 = (p - foot).squaredNorm(), line = nrm.dot(p - a);
      const double tie = 1e-12 * e.squaredNorm();  // (the same vertex through two segments, to round-off)
      if (d2 < best_d2 - tie) {
        best_d2 = d2;
        best_line = std::abs(line);
        best.foot = foot;
        best.inside = line < 0;
        at_end = u <= 0 || u >= 1;
        reached = 1;
        normal_sum = nrm;
      } else if (d2 <= best_d2 + tie) {  // the same vertex, reached through another segment
        ++reached;
        normal_sum += nrm;
        if (std::abs(line) > best_line) {
          best_line = std::abs(line);
          best.inside = line < 0;
        }
      }
    }
  }
  if (!std::isfinite(best_d2)) return best;
  if (at_end && reached < 2) best.inside = false;
  best.depth = best.inside ? std::sqrt(best_d2) : -std::sqrt(best_d2);
  best.normal = normal_sum.norm() > 1e-12 ? Vec2(normal_sum.normalized()) : Vec2::Zero();
  return best;
}

void WallParticles::keep_inside_walls(ParticleCloud& cloud, const FluidMesh& mesh, const Vec& x_start, double t) {
  // A fluid particle in no element with a wall's particles (a drop flying ballistically) is not held by
  // the wall, and a fast one may pass between the particles of its element: in one step it can cross the
  // wall (a drop at 4 m/s moves 0.8 h a step at h = 5 mm, dt = 1 ms). Without this check the drops were
  // lost through the walls and dropped at the domain box (1.3 % of the fluid in elastic_obstacle_walhorn by
  // 1 s). A particle is put back 0.05 h on the fluid side of the walls' nearest point, and loses the velocity
  // component into the wall (an inelastic impact), if
  //  - it ends deeper than the tolerance (below) in the solid behind the sided segments (those with the initial
  //    fluid on one side), having started at most that deep: the depth is its distance to the nearest point of
  //    those segments, inside when it lies behind the segment (or, at a vertex, behind the one of the segments
  //    meeting there whose line it is furthest from), so that a corner between two walls (a cylinder and the
  //    plate behind it) is closed as well as a corner of one polyline (a particle there was past the end of
  //    every segment, slid into the plate and the mesh filled the solid); or
  //  - its path x_n -> x_{n+1} crossed a segment with fluid on both sides (the side it came from is then the
  //    fluid side).
  // The tolerance is 0.5 h. A particle in an element with a wall particle is held by the mesh, and its excursions
  // across the wall line of up to one spacing (a film sliding on the floor between the no-slip particles) are the
  // discretization's: only a held particle more than h deep is put back (putting back the film's particles at
  // 0.25 h made the film at a dam-break toe run ahead: dam_break_floor front RMS 0.21 -> 0.50).
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
    auto put_back = [&](const Vec2& foot, const Vec2& nrm) {
      p1 = foot + 0.05 * cloud.h(i) * nrm;
      Vec2 v = vel.segment<2>(2 * i);
      const double vn = v.dot(nrm);
      if (vn < 0) v -= vn * nrm;
      vel.segment<2>(2 * i) = v;
      ++wall_crossings_;
    };
    const SolidDepth end = solid_depth(p1, t);
    if (end.depth > tol && solid_depth(p0, t).depth <= tol) put_back(end.foot, end.normal);
    for (const auto& w : walls_) {
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        if (w.fluid_side[k] != 0) continue;
        const Vec2 a = w.point_at(w.polyline[k], t), e = w.point_at(w.polyline[k + 1], t) - a;
        const Vec2 d = p1 - p0;
        const double den = cross(d, e);
        if (std::abs(den) <= 1e-300) continue;  // parallel
        const double s = cross(a - p0, e) / den, u = cross(a - p0, d) / den;
        if (!(s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0)) continue;
        Vec2 nrm = w.normal_at(k, t);
        if (nrm.dot(p0 - a) < 0) nrm = -nrm;  // towards the side the particle came from
        if (nrm.dot(p1 - a) > -tol) continue;
        put_back(a + u * e, nrm);
      }
    }
    x.segment<2>(2 * i) = p1;
  }
}

}  // namespace lagfsi::fluid
