#pragma once
/// @file mesh.hpp
/// Triangle meshes of order 1, 2 and 3 (T3, T6, T10) with straight or curved sides.
///
/// Local node numbering (the same as VTK's Lagrange triangle, so output needs no reordering):
///  - vertices 0, 1, 2 (counter-clockwise);
///  - T6: 3 on edge 0-1, 4 on edge 1-2, 5 on edge 2-0 (mid-points);
///  - T10: 3,4 on edge 0-1 (at 1/3 and 2/3 from vertex 0), 5,6 on edge 1-2 (from vertex 1),
///         7,8 on edge 2-0 (from vertex 2), 9 at the centroid.
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi {

struct TriMesh {
  int order = 1;            ///< 1 (T3), 2 (T6) or 3 (T10)
  std::vector<Vec2> nodes;  ///< nodal coordinates
  std::vector<Index> conn;  ///< nodes_per_element() indices per element, element after element

  static constexpr int nodes_per_element(int order) { return (order + 1) * (order + 2) / 2; }
  int nodes_per_element() const { return nodes_per_element(order); }
  Index num_nodes() const { return static_cast<Index>(nodes.size()); }
  Index num_elements() const { return static_cast<Index>(conn.size() / nodes_per_element()); }
  const Index* element(Index e) const { return conn.data() + static_cast<size_t>(e) * nodes_per_element(); }
};

/// An edge of the mesh boundary: its element, the local edge (0: 0-1, 1: 1-2, 2: 2-0) and its
/// order+1 nodes in order from the first vertex to the second (vertices first and last).
struct BoundaryEdge {
  Index element;
  int local_edge;
  std::vector<Index> nodes;
};

/// Boundary edges of a mesh (edges used by a single element).
std::vector<BoundaryEdge> boundary_edges(const TriMesh& mesh);

}  // namespace lagfsi
