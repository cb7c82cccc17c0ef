#pragma once
/// @file previous_domain.hpp
/// The fluid domain of the last step carried to the particles' present positions: its elements, moved with
/// their particles (the mesh the last step was solved on, at x_{n+1}), and its boundary edges. It is the
/// predicate of the conservative PFEM domain detections (remesh.hpp, DomainDetection):
///  - "advected" (Leyssens, Lambrechts & Remacle, UCLouvain: quality-based PFEM refinement in 2D, 2024,
///    arXiv:2403.18416, and "Three-dimensional mesh adaptation in PFEM", arXiv:2512.20347, 2025): a new
///    Delaunay element whose centroid lies in the advected domain is fluid; outside it only the alpha test
///    can add an element (two surfaces or a surface and a wall meeting);
///  - "level_set" (Fernandez & Ponthot, ULiège, ECCOMAS 2024; Fernandez et al. 2023, arXiv:2305.00228): the
///    signed distance to the advected boundary replaces the alpha test: an element is fluid if its centroid
///    is inside or within a band outside.
/// Point location and distances use a uniform grid of buckets (cell about one element), so a query costs
/// O(1) for a mesh of uniform spacing. No CGAL: plain geometry on lagfsi types.
#include <lagfsi/types.hpp>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace lagfsi::meshing {

class PreviousDomain {
 public:
  PreviousDomain() = default;
  /// `triangles`: the advected elements' corners (any orientation; an element inverted by the step still
  /// counts with its present corners); `boundary`: the edges used by exactly one element.
  PreviousDomain(std::vector<std::array<Vec2, 3>> triangles, std::vector<std::array<Vec2, 2>> boundary);

  bool empty() const { return triangles_.empty(); }
  std::size_t size() const { return triangles_.size(); }
  /// p lies in (or on the border of, to 1e-12 relative) one of the elements.
  bool contains(const Vec2& p) const;
  /// Distance from p to the nearest boundary edge if it is below `limit`, otherwise `limit`.
  double boundary_distance(const Vec2& p, double limit) const;
  /// Total (unsigned) area of the elements.
  double area() const;

  /// The previous mesh's topology in the numbering of the particles about to be triangulated (after particle
  /// management): which particles it used, and its boundary edges (pairs in either order). Optional; without
  /// it every particle counts as meshed and no edge as a boundary edge.
  void set_topology(std::vector<std::uint8_t> meshed, std::vector<std::pair<Index, Index>> boundary_edges);
  bool meshed(Index i) const;
  bool is_boundary_edge(Index a, Index b) const;
  /// The boundary edges given to set_topology, as (min, max) pairs, sorted.
  const std::vector<std::pair<Index, Index>>& boundary_edges() const { return boundary_edges_; }
  /// Every edge of the previous mesh (boundary and interior) in the same numbering, for keeping its
  /// connectivity (RemeshSettings::keep_edges_angle). Optional; without it only boundary edges are kept.
  void set_edges(std::vector<std::pair<Index, Index>> edges);
  const std::vector<std::pair<Index, Index>>& edges() const { return edges_; }
  bool is_edge(Index a, Index b) const;

 private:
  struct Grid {
    Vec2 lo = Vec2::Zero();
    double cell = 1;
    int nx = 0, ny = 0;
    std::vector<int> start;  // CSR: bucket b holds items[start[b] .. start[b + 1])
    std::vector<int> items;
    int cx(double x) const;
    int cy(double y) const;
  };
  /// Buckets every item (given by its bounding box) in the cells it overlaps.
  static Grid bucket(const std::vector<std::array<Vec2, 2>>& boxes, const Vec2& lo, const Vec2& hi, double cell);

  std::vector<std::uint8_t> meshed_;
  std::vector<std::pair<Index, Index>> boundary_edges_;  // (min, max), sorted
  std::vector<std::pair<Index, Index>> edges_;           // (min, max), sorted, unique
  std::vector<std::array<Vec2, 3>> triangles_;
  std::vector<double> sign_, tolerance_;  // per element: its orientation (0: flat) and contains()' tolerance
  std::vector<std::array<Vec2, 2>> boundary_;
  Grid tri_grid_, edge_grid_;
};

}  // namespace lagfsi::meshing
