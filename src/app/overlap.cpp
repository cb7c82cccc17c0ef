// Overlap of plane regions (overlap.hpp).
//
// Area: with any point O, the indicator of a simple polygon a_0 ... a_{n-1} is, almost everywhere,
// sum_i s_i 1[T_i] with T_i the triangle (O, a_i, a_{i+1}) and s_i the sign of its orientation divided by the
// polygon's (the winding number, normalised). So |A ∩ B| = sum_i sum_j s_i s_j |T_i ∩ T_j|, each term the
// area of the intersection of two triangles (convex clipping, Sutherland-Hodgman); holes enter with the
// opposite sign. Exact up to rounding for non-convex polygons, O(n m) for n and m vertices; O is the centre
// of the two regions' bounding box, which keeps the cancellation small.
#include "overlap.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi {

namespace {

double signed_area(const std::vector<Vec2>& p) {
  double s = 0;
  for (size_t i = 0; i < p.size(); ++i) s += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * s;
}

/// Clips the convex polygon `poly` by the half-plane left of the directed line a -> b.
std::vector<Vec2> clip(const std::vector<Vec2>& poly, const Vec2& a, const Vec2& b) {
  std::vector<Vec2> out;
  const Vec2 d = b - a;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    const double sp = cross(d, p - a), sq = cross(d, q - a);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  return out;
}

/// Area of the intersection of two counter-clockwise triangles.
double triangle_overlap(const std::vector<Vec2>& t, const std::vector<Vec2>& u) {
  std::vector<Vec2> p = t;
  for (int k = 0; k < 3 && p.size() >= 3; ++k) p = clip(p, u[k], u[(k + 1) % 3]);
  return p.size() >= 3 ? std::max(0.0, signed_area(p)) : 0.0;
}

/// The fan triangles (O, a_i, a_{i+1}) of every ring of a region, counter-clockwise, with their weights.
struct Fan {
  std::vector<std::vector<Vec2>> triangles;
  std::vector<double> weight;
  Vec2 lo, hi;
};

Fan fan_of(const PlaneRegion& r, const Vec2& o) {
  Fan f;
  f.lo = Vec2::Constant(INFINITY);
  f.hi = -f.lo;
  for (size_t k = 0; k < r.rings.size(); ++k) {
    const auto& ring = r.rings[k];
    const double area = signed_area(ring);
    if (ring.size() < 3 || area == 0) continue;
    const double ring_sign = (area > 0 ? 1.0 : -1.0) * (k == 0 ? 1.0 : -1.0);
    for (size_t i = 0; i < ring.size(); ++i) {
      const Vec2 &a = ring[i], &b = ring[(i + 1) % ring.size()];
      f.lo = f.lo.cwiseMin(a);
      f.hi = f.hi.cwiseMax(a);
      const double s = cross(a - o, b - o);
      if (s == 0) continue;
      f.triangles.push_back(s > 0 ? std::vector<Vec2>{o, a, b} : std::vector<Vec2>{o, b, a});
      f.weight.push_back(ring_sign * (s > 0 ? 1.0 : -1.0));
    }
  }
  return f;
}

Vec2 box_centre(const PlaneRegion& a, const PlaneRegion& b) {
  Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
  for (const auto* r : {&a, &b})
    for (const auto& ring : r->rings)
      for (const auto& p : ring) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  return 0.5 * (lo + hi);
}

bool inside(const PlaneRegion& r, const Vec2& q) {
  bool in = false;
  for (const auto& ring : r.rings)
    for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Vec2 &a = ring[i], &b = ring[j];
      if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
        in = !in;
    }
  return in;
}

double distance_to_boundary(const PlaneRegion& r, const Vec2& q) {
  double d = INFINITY;
  for (const auto& ring : r.rings)
    for (size_t i = 0; i < ring.size(); ++i) {
      const Vec2 &a = ring[i], &b = ring[(i + 1) % ring.size()];
      const Vec2 ab = b - a;
      const double l2 = ab.squaredNorm();
      const double s = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      d = std::min(d, (q - (a + s * ab)).norm());
    }
  return d;
}

}  // namespace

double region_area(const PlaneRegion& r) {
  double a = 0;
  for (size_t k = 0; k < r.rings.size(); ++k) a += (k == 0 ? 1 : -1) * std::abs(signed_area(r.rings[k]));
  return a;
}

double overlap_area(const PlaneRegion& a, const PlaneRegion& b) {
  const Vec2 o = box_centre(a, b);
  const Fan fa = fan_of(a, o), fb = fan_of(b, o);
  if (fa.triangles.empty() || fb.triangles.empty()) return 0;
  if ((fa.hi.array() <= fb.lo.array()).any() || (fb.hi.array() <= fa.lo.array()).any()) return 0;
  double s = 0;
  for (size_t i = 0; i < fa.triangles.size(); ++i)
    for (size_t j = 0; j < fb.triangles.size(); ++j)
      s += fa.weight[i] * fb.weight[j] * triangle_overlap(fa.triangles[i], fb.triangles[j]);
  return std::max(0.0, s);
}

double length_inside(const PlaneRegion& r, const std::vector<Vec2>& polyline, double eps) {
  double total = 0;
  for (size_t s = 0; s + 1 < polyline.size(); ++s) {
    const Vec2 p = polyline[s], d = polyline[s + 1] - p;
    // Parameters where the segment meets a ring's edge: between two of them it is inside or outside.
    std::vector<double> cuts{0.0, 1.0};
    for (const auto& ring : r.rings)
      for (size_t i = 0; i < ring.size(); ++i) {
        const Vec2 &a = ring[i], e = ring[(i + 1) % ring.size()] - ring[i];
        const double den = cross(d, e);
        if (den == 0) continue;  // parallel: an edge along the segment adds no crossing
        const double t = cross(a - p, e) / den, u = cross(a - p, d) / den;
        if (t > 0 && t < 1 && u >= 0 && u <= 1) cuts.push_back(t);
      }
    std::sort(cuts.begin(), cuts.end());
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
      const Vec2 mid = p + 0.5 * (cuts[k] + cuts[k + 1]) * d;
      if (inside(r, mid) && distance_to_boundary(r, mid) > eps) total += (cuts[k + 1] - cuts[k]) * d.norm();
    }
  }
  return total;
}

}  // namespace lagfsi
