// What all structural discretisations share: surface points as linear combinations of dof nodes, dead
// tractions and follower pressure on surface edges.
#include <lagfsi/element.hpp>
#include <lagfsi/solid/solid.hpp>

#include <stdexcept>

namespace lagfsi {

namespace {

Vec2 point_value(const SurfacePoint& p, const Vec& full) {
  Vec2 x = full.segment<2>(2 * p.node);
  if (p.other >= 0) x += p.c * full.segment<2>(2 * p.other);
  return x;
}

}  // namespace

Vec StructuralBody::surface_values(const std::vector<Index>& points, const Vec& full) const {
  const auto& sp = surface_points();
  Vec out(2 * points.size());
  for (size_t k = 0; k < points.size(); ++k) out.segment<2>(2 * k) = point_value(sp[points[k]], full);
  return out;
}

void StructuralBody::add_surface_forces(const std::vector<Index>& points, const Vec& forces, Vec& full) const {
  const auto& sp = surface_points();
  for (size_t k = 0; k < points.size(); ++k) {
    const SurfacePoint& p = sp[points[k]];
    full.segment<2>(2 * p.node) += forces.segment<2>(2 * k);
    if (p.other >= 0) full.segment<2>(2 * p.other) += p.c * forces.segment<2>(2 * k);
  }
}

Vec surface_traction(const StructuralBody& body, const std::vector<std::vector<Index>>& edges, const Vec2& t) {
  const int p = body.surface_order();
  const Vec& X = body.reference_positions();
  Vec f = Vec::Zero(body.num_dofs());
  Eigen::VectorXd N, dN;
  for (const auto& edge : edges) {
    if (static_cast<int>(edge.size()) != p + 1) throw std::invalid_argument("edge has the wrong number of nodes");
    std::vector<Index> pts(edge.begin(), edge.end());
    const Vec Xe = body.surface_values(pts, X);
    Vec fe = Vec::Zero(2 * (p + 1));
    for (const auto& [s, w] : line_quadrature(p + 1)) {
      line_shape(p, s, N, dN);
      Vec2 dXds = Vec2::Zero();
      for (int a = 0; a <= p; ++a) dXds += dN[a] * Xe.segment<2>(2 * a);
      const double dS = w * dXds.norm() * body.out_of_plane();
      for (int a = 0; a <= p; ++a) fe.segment<2>(2 * a) += N[a] * dS * t;
    }
    body.add_surface_forces(pts, fe, f);
  }
  return f;
}

SparseMatrix follower_pressure_matrix(const StructuralBody& body, const std::vector<std::vector<Index>>& edges) {
  const int p = body.surface_order();
  const auto& sp = body.surface_points();
  const double b = body.out_of_plane();
  // Edge matrix C_ab = int N_a dN_b/ds ds (exact with p+1 Gauss points: degree 2p-1).
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(p + 1, p + 1);
  Eigen::VectorXd N, dN;
  for (const auto& [s, w] : line_quadrature(p + 1)) {
    line_shape(p, s, N, dN);
    C += w * N * dN.transpose();
  }
  // f_a = -p b sum_b C_ab (y_b, -x_b) for point positions x_b (outward normal on the right of the edge);
  // per unit pressure, on the point coordinates: f_ax = -b C_ab y_b, f_ay = +b C_ab x_b. Chained through
  // the points' linear maps onto dof nodes.
  SparseMatrix P = body.pattern();
  double* val = P.valuePtr();
  std::fill(val, val + P.nonZeros(), 0.0);
  const Index nnz = P.nonZeros();
  auto add = [&](Index row, Index col, double v) { P.coeffRef(row, col) += v; };
  for (const auto& edge : edges) {
    if (static_cast<int>(edge.size()) != p + 1) throw std::invalid_argument("edge has the wrong number of nodes");
    for (int a = 0; a <= p; ++a)
      for (int bb = 0; bb <= p; ++bb) {
        const double c = b * C(a, bb);
        if (c == 0.0) continue;
        const SurfacePoint& pa = sp[edge[a]];
        const SurfacePoint& pb = sp[edge[bb]];
        const Index ra[2] = {pa.node, pa.other};
        const double wa[2] = {1.0, pa.c};
        const Index rb[2] = {pb.node, pb.other};
        const double wb[2] = {1.0, pb.c};
        for (int i = 0; i < 2; ++i) {
          if (ra[i] < 0) continue;
          for (int j = 0; j < 2; ++j) {
            if (rb[j] < 0) continue;
            const double v = c * wa[i] * wb[j];
            add(2 * ra[i], 2 * rb[j] + 1, -v);  // f_x from y
            add(2 * ra[i] + 1, 2 * rb[j], v);   // f_y from x
          }
        }
      }
  }
  // An edge's points belong to one element, so no entry may have been inserted outside the pattern.
  if (P.nonZeros() != nnz) throw std::logic_error("follower pressure: an edge spans more than one element");
  return P;
}

}  // namespace lagfsi
