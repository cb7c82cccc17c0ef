#pragma once
/// @file primitives.hpp
/// Initial meshing of geometric primitives (CGAL constrained Delaunay + Delaunay refinement, or a
/// structured pattern), and elevation of linear meshes to T6/T10 with straight sides.
/// CGAL types do not appear here; see meshing/src.
#include <lagfsi/mesh.hpp>
#include <lagfsi/types.hpp>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagfsi::meshing {

/// A polygonal region: counter-clockwise outer loop, clockwise or counter-clockwise holes
/// (orientation of holes does not matter). Loops are not closed (last point != first point).
struct PolygonRegion {
  std::vector<Vec2> outer;
  std::vector<std::vector<Vec2>> holes;
};

/// mesh_polygon's refusal of a mesh past its `max_elements` (an std::invalid_argument like its other refusals):
/// the caller, which set the limit, can say how to raise it.
struct MeshTooLarge : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Unstructured linear mesh of the region with target edge size h (boundary segments are split to
/// at most h first, so that the boundary node spacing is about h; then CGAL's Delaunay mesher refines
/// with the size criterion h and the shape criterion (minimum angle about 20.7 degrees)).
/// Throws std::invalid_argument for a degenerate region (fewer than 3 points, zero area,
/// self-intersecting loop, h <= 0 or h not finite, a feature thinner than h/50, or more than `max_elements`
/// elements: expected from the area before meshing, or counted during the refinement, which small input
/// angles can drive far beyond the area's estimate; that one as MeshTooLarge).
/// A graded mesh: `size` (when given) is the local target edge size at a point, at least h (the boundary is
/// still split at h, the finest size, and the faces are refined until their longest edge is below the size at
/// their centroid); its gradation is the caller's (a size that grows by g per unit length gives elements that
/// grow by about g per layer).
TriMesh mesh_polygon(const PolygonRegion& region, double h, double max_elements = 5e6,
                     const std::function<double(const Vec2&)>& size = nullptr);

/// Structured linear mesh of the rectangle [x0, x1] x [y0, y1] with nx x ny cells, each cut into two
/// triangles. pattern: "right" (all diagonals bottom-left to top-right), "left", or "crossed"
/// (alternating, symmetric). Throws std::invalid_argument for nx, ny < 1 or an empty rectangle.
TriMesh mesh_rectangle_structured(double x0, double y0, double x1, double y1, int nx, int ny,
                                  const std::string& pattern = "crossed");

/// Elevates a linear (T3) mesh to order 2 or 3 with straight sides; nodes on a shared edge are shared
/// (created once per edge, with the edge's orientation respected for T10). Order 1 returns a copy.
TriMesh elevate(const TriMesh& linear, int order);

/// Polygon approximation of a circle arc from angle a0 to a1 (radians, counter-clockwise if a1 > a0)
/// with segments no longer than h; the end points are included.
std::vector<Vec2> arc_points(const Vec2& centre, double radius, double a0, double a1, double h);

}  // namespace lagfsi::meshing
