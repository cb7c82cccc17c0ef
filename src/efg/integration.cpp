// Integration-consistent derivative correction on background cells. See src/efg/include/lagfsi/efg/integration.hpp.
#include <lagfsi/efg/integration.hpp>

#include <Eigen/Dense>

namespace lagfsi::efg {

void correct_derivatives(int degree, const std::vector<Vec2>& xg, const std::vector<double>& wg,
                         const Eigen::MatrixXd& N, const std::vector<Vec2>& xe, const std::vector<Vec2>& wn,
                         const Eigen::MatrixXd& Ne, Eigen::MatrixXd& Nx, Eigen::MatrixXd& Ny) {
  const int ng = static_cast<int>(xg.size()), ne = static_cast<int>(xe.size()), nn = static_cast<int>(N.cols());
  const int nq = degree >= 2 ? 3 : 1;
  // Q about the cell centre, scaled (conditioning).
  Vec2 c = Vec2::Zero();
  for (const auto& x : xg) c += x / ng;
  double s = 0;
  for (const auto& x : xg) s = std::max(s, (x - c).cwiseAbs().maxCoeff());
  if (s <= 0) s = 1;
  auto q = [&](const Vec2& x, double* v, double* vx, double* vy) {
    const Vec2 d = (x - c) / s;
    v[0] = 1;
    vx[0] = vy[0] = 0;
    if (nq == 3) {
      v[1] = d.x();
      v[2] = d.y();
      vx[1] = 1 / s;
      vx[2] = 0;
      vy[1] = 0;
      vy[2] = 1 / s;
    }
  };
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nq, nq);  // sum_g w q r
  Eigen::MatrixXd Qg(ng, nq), Qgx(ng, nq), Qgy(ng, nq), Qe(ne, nq);
  for (int g = 0; g < ng; ++g) {
    double v[3], vx[3], vy[3];
    q(xg[g], v, vx, vy);
    for (int a = 0; a < nq; ++a) {
      Qg(g, a) = v[a];
      Qgx(g, a) = vx[a];
      Qgy(g, a) = vy[a];
    }
  }
  for (int e = 0; e < ne; ++e) {
    double v[3], vx[3], vy[3];
    q(xe[e], v, vx, vy);
    for (int a = 0; a < nq; ++a) Qe(e, a) = v[a];
  }
  for (int g = 0; g < ng; ++g) G += wg[g] * Qg.row(g).transpose() * Qg.row(g);
  const Eigen::MatrixXd Gi = G.inverse();
  Eigen::VectorXd wx(ne), wy(ne);
  for (int e = 0; e < ne; ++e) {
    wx[e] = wn[e].x();
    wy[e] = wn[e].y();
  }
  const Eigen::Map<const Eigen::VectorXd> w(wg.data(), ng);
  // Per node I and direction i: target_q - current_q = G a.
  // target_x = Qe^T diag(wx) Ne - Qgx^T diag(w) N ; current_x = Qg^T diag(w) Nx.   (nq x nn)
  const Eigen::MatrixXd tx = Qe.transpose() * wx.asDiagonal() * Ne - Qgx.transpose() * w.asDiagonal() * N;
  const Eigen::MatrixXd ty = Qe.transpose() * wy.asDiagonal() * Ne - Qgy.transpose() * w.asDiagonal() * N;
  const Eigen::MatrixXd ax = Gi * (tx - Qg.transpose() * w.asDiagonal() * Nx);
  const Eigen::MatrixXd ay = Gi * (ty - Qg.transpose() * w.asDiagonal() * Ny);
  Nx += Qg * ax;
  Ny += Qg * ay;
  (void)nn;
}

}  // namespace lagfsi::efg
