#pragma once
/// @file geometry2d.hpp
/// Plane-geometry helpers shared by the modules (walls, contacts, remeshing, input checks): one definition of
/// each instead of a copy per file.
#include <lagfsi/types.hpp>

#include <algorithm>

namespace lagfsi {

/// The z component of a x b: twice the signed area of the triangle (0, a, b), positive counter-clockwise.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The closest point of the segment [a, b] to c (a itself for a degenerate segment).
inline Vec2 closest_on_segment(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0 ? std::clamp((c - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

/// The distance from p to the segment [a, b].
inline double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  return (p - closest_on_segment(a, b, p)).norm();
}

}  // namespace lagfsi
