#pragma once
/// @file discretization.hpp
/// The EFG discretisation (thesis §2.6-2.7, §4.3-4.4; digest shared/spec/003_efg.md §2.5-2.7):
///  - a quadrilateral background mesh whose corners are the nodes ("unified nodes": particles, integration-cell
///    corners and coupling-element nodes are one node set with one dof pair each);
///  - node domain sizes rho_j = alpha h_j (h_j: the largest width/height of the cells around node j);
///  - protected segments and the visibility criterion (Belytschko et al. 1996): node j is not in the support of
///    x when segment x-x_j crosses a protected segment (re-entrant corners);
///  - a bucket grid for the support search (the thesis's O(n^2) search, replaced: its §6 future work);
///  - Gauss-Legendre rules of any order on the cells, Q4 shape functions of a cell (the coupling elements).
#include <lagfsi/types.hpp>

#include <array>
#include <vector>

namespace lagfsi::efg {

/// Quadrilateral mesh: corners counter-clockwise. A quadratic mesh (q9 not empty) also has the mid-side and centre
/// nodes of each cell: q9[c] = corners 0-3 (as cells[c]), mid-sides of the edges 0-1, 1-2, 2-3, 3-0, centre; its
/// cells are then the Q9 coupling elements (thesis §5.3: the 9-term basis needs Q9 coupling elements) and its node
/// spacing is half the cell width. The geometry of a cell is always the bilinear map of its corners (straight edges,
/// mid-side nodes at the middle: the Q9 map is then the same).
struct QuadMesh {
  std::vector<Vec2> nodes;
  std::vector<std::array<Index, 4>> cells;
  std::vector<std::array<Index, 9>> q9;
  Index num_nodes() const { return static_cast<Index>(nodes.size()); }
  Index num_cells() const { return static_cast<Index>(cells.size()); }
  bool quadratic() const { return !q9.empty(); }
  int nodes_per_cell() const { return quadratic() ? 9 : 4; }
  /// Node a (0 .. nodes_per_cell() - 1) of cell c.
  Index cell_node(Index c, int a) const { return quadratic() ? q9[c][a] : cells[c][a]; }
};

/// Natural coordinates of the local node a of a Q4 / Q9 cell (corners, mid-sides, centre).
void cell_node_natural(int a, double& xi, double& eta);

/// Structured nx x ny grid of a rectangle (order 2: Q9 cells, (2 nx + 1) x (2 ny + 1) nodes); cells whose centre lies
/// in one of `holes` (boxes min/max) are removed, and so are the nodes left without a cell (an L-shaped panel = a
/// rectangle minus a box).
QuadMesh rectangle_grid(Vec2 origin, Vec2 size, int nx, int ny, const std::vector<std::array<Vec2, 2>>& holes = {},
                        int order = 1);

/// Quarter of a square plate [0, b]^2 with a circular hole of radius a at the origin: two mapped blocks split on
/// the diagonal, n_arc cells along each half of the arc and n_rad radially, radially graded by `grading`
/// (ratio of the outermost to the innermost radial cell size).
QuadMesh plate_with_hole(double a, double b, int n_arc, int n_rad, double grading = 1.0);

/// Edges used by one cell (the boundary), as (cell, local edge k: corners k, k+1).
std::vector<std::array<Index, 2>> boundary_cell_edges(const QuadMesh& m);

/// Q4 shape functions and derivatives with respect to (xi, eta) in [-1, 1]^2.
void q4_shape(double xi, double eta, double N[4], double dxi[4], double deta[4]);
/// Q9 (biquadratic Lagrange) shape functions and derivatives, the node order of QuadMesh::q9.
void q9_shape(double xi, double eta, double N[9], double dxi[9], double deta[9]);

/// Gauss-Legendre points and weights on [-1, 1] (n = 1..12).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w);

/// Protected segments and the visibility test.
struct Visibility {
  std::vector<std::array<Vec2, 2>> segments;
  /// True if the segment a-b crosses no protected segment (touching an end point counts as crossing only
  /// when the crossing is proper; a node lying on a protected segment sees its side).
  bool visible(const Vec2& a, const Vec2& b) const;
};

/// Nodes in buckets of a uniform grid: the candidates within a box.
class NodeSearch {
 public:
  NodeSearch() = default;
  NodeSearch(const std::vector<Vec2>& nodes, double cell_size);
  /// Nodes with |x - x_j| <= r componentwise (a superset of any domain of size <= r).
  void within(const Vec2& x, double r, std::vector<Index>& out) const;

 private:
  const std::vector<Vec2>* nodes_ = nullptr;
  Vec2 lo_ = Vec2::Zero();
  double h_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<Index>> bucket_;
};

}  // namespace lagfsi::efg
