#pragma once
/// @file element.hpp
/// Lagrange triangles of order 1-3 on the parent triangle {xi1 >= 0, xi2 >= 0, xi1 + xi2 <= 1}
/// (area coordinates L1 = xi1, L2 = xi2, L3 = 1 - xi1 - xi2; vertex 0 at L1 = 1, vertex 1 at L2 = 1,
/// vertex 2 at L3 = 1), node numbering as in mesh.hpp, and symmetric Gauss rules on triangles.
///
/// Shape functions (Zienkiewicz & Taylor, vol. 1, 6th ed., sec. 6.5):
///  - T3: N_i = L_i
///  - T6: vertices L_i (2 L_i - 1), edge mid-nodes 4 L_i L_j
///  - T10: vertices L_i (3 L_i - 1)(3 L_i - 2)/2, edge nodes 9/2 L_i L_j (3 L_i - 1) (the node nearer
///    vertex i), centroid 27 L1 L2 L3.
///
/// Quadrature: Dunavant (1985), Int. J. Numer. Meth. Eng. 21:1129, exact for polynomials of the
/// stated degree; weights sum to 1/2 (the parent area).
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi {

struct QuadraturePoint {
  double xi1, xi2, weight;
};

/// A rule exact for polynomials of total degree `degree` (1 to 8 supported; a higher request throws
/// std::invalid_argument). Degrees without a dedicated rule use the next higher one.
const std::vector<QuadraturePoint>& triangle_quadrature(int degree);

/// Rule on [0, 1] (Gauss-Legendre, n points, exact to degree 2n-1), for boundary edges.
const std::vector<std::pair<double, double>>& line_quadrature(int n_points);

/// Values and parent-space derivatives of the shape functions of an order-p triangle at (xi1, xi2).
/// N has n = (p+1)(p+2)/2 entries; dN is n x 2 (columns d/dxi1, d/dxi2).
void triangle_shape(int order, double xi1, double xi2, Eigen::VectorXd& N, Eigen::MatrixX2d& dN);

/// Values and derivatives (d/ds, s in [0, 1]) of the order+1 shape functions on an edge, nodes ordered
/// from the first vertex (s = 0) to the second (s = 1), equally spaced.
void line_shape(int order, double s, Eigen::VectorXd& N, Eigen::VectorXd& dN);

/// Parent coordinates of the local nodes of an order-p triangle (for elevation and tests).
std::vector<std::pair<double, double>> triangle_node_coordinates(int order);

}  // namespace lagfsi
