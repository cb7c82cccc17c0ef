// "wall_model": "particles" (fluid_walls.hpp): placing the walls' particles, and putting back the fluid particles
// whose step crossed a wall.
#include "fluid_walls.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>

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

void WallParticles::keep_inside_walls(ParticleCloud& cloud, const FluidMesh& mesh, const Vec& x_start, double t) {
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
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        const Vec2 a = w.point_at(w.polyline[k], t), b = w.point_at(w.polyline[k + 1], t), e = b - a;
        Vec2 nrm = w.normal_at(k, t);
        double u;  // where the particle goes back, along the segment
        if (w.fluid_side[k] != 0) {
          u = (p1 - a).dot(e) / e.squaredNorm();
          // Past an end of the segment by less than tol, at a corner whose other segment the particle is
          // beyond as well (the outer quadrant of a tank's corner): a film sliding along the floor a little
          // below it would otherwise leave through the corner, in neither segment's span (dam_break_tank with
          // the level-set detection lost particles there). Put back at the corner.
          const double reach = tol / e.norm();
          const bool past_end = (u < 0 && u >= -reach && k > 0 && w.beyond_line(k - 1, p1, t)) ||
                                (u > 1 && u <= 1 + reach && k + 2 < w.polyline.size() && w.beyond_line(k + 1, p1, t));
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
