// Fixed connectivity (fluid_walls.hpp): the mesh's nodes on a wall constrained once, for the whole run.
#include "fluid_walls.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::fluid {

void FixedMeshWalls::constrain_fixed_mesh(const Params& body, const std::vector<Vec2>& pts, double h, bool frames) {
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

}  // namespace lagfsi::fluid
