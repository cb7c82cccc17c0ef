#pragma once
// Plane geometry of the overlap checks (overlap.cpp): the area two regions share and the length of a polyline
// inside a region. A region is an outer ring and holes (simple polygons, either orientation).
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi {

struct PlaneRegion {
  std::vector<std::vector<Vec2>> rings;  ///< rings[0]: the outline; the others: holes in it
};

/// Area of the region (outline minus holes).
double region_area(const PlaneRegion& r);

/// Area of the intersection of two regions (0 when they only touch).
double overlap_area(const PlaneRegion& a, const PlaneRegion& b);

/// Length of the polyline that lies inside the region farther than `eps` from its boundary (a wall along an
/// edge of the region, or ending on it, gives 0).
double length_inside(const PlaneRegion& r, const std::vector<Vec2>& polyline, double eps);

}  // namespace lagfsi
