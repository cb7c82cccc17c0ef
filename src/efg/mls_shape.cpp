// MLS shape functions and first derivatives by the gamma formulation, with the moment-matrix conditioning
// check and the FE-EFG coupling correction (thesis Eqs. 2.26-2.31, 2.85-2.89, Algorithm 5). See mls.hpp.
#include <lagfsi/efg/mls.hpp>
#include <lagfsi/error.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace lagfsi::efg {

namespace {
using MatL = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9>;
using VecL = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 9, 1>;

std::string where_text(const Vec2& x, const std::string& where) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "MLS at (%.6g, %.6g)", x.x(), x.y());
  return std::string(buf) + (where.empty() ? "" : " [" + where + "]");
}
}  // namespace

void MlsShape::compute(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<Vec2>& rho,
                       const std::vector<Index>& support, ShapeValues& out, const FeCorrection* fe,
                       const std::string& where, bool derivatives) const {
  const int l = basis_.size();
  out.nodes.clear();
  out.N.clear();
  out.Nx.clear();
  out.Ny.clear();
  // Weights of the support; scale s = mean domain size (the shifted, scaled basis p((y - x)/s)).
  thread_local std::vector<double> w, wx, wy;
  thread_local std::vector<double> P;  // p((x_j - x)/s), l per node
  w.clear();
  wx.clear();
  wy.clear();
  double s = 0;
  for (Index j : support) {
    if (!domain_.contains(x, nodes[j], rho[j])) continue;
    double a, ax, ay;
    domain_.eval(x, nodes[j], rho[j], a, ax, ay);
    if (!(a > 0)) continue;
    out.nodes.push_back(j);
    w.push_back(a);
    wx.push_back(ax);
    wy.push_back(ay);
    s += 0.5 * (rho[j].x() + (domain_.shape == DomainShape::circular ? rho[j].x() : rho[j].y()));
  }
  const int n = static_cast<int>(out.nodes.size());
  if (n == 0 && !fe)
    throw SolverError(where_text(x, where) + ": no node's influence domain contains the point (enlarge alpha)");
  if (n == 0) {  // a coupled point with no particle: pure FE there
    out.rcond = 1;
    return;
  }
  s /= n;
  P.resize(static_cast<size_t>(n) * l);
  MatL M = MatL::Zero(l, l), Mx = MatL::Zero(l, l), My = MatL::Zero(l, l);
  for (int k = 0; k < n; ++k) {
    const Vec2 d = (nodes[out.nodes[k]] - x) / s;
    double* pk = &P[static_cast<size_t>(k) * l];
    basis_.eval(d.x(), d.y(), pk, nullptr, nullptr);
    Eigen::Map<const VecL> pv(pk, l);
    M.noalias() += w[k] * pv * pv.transpose();
    Mx.noalias() += wx[k] * pv * pv.transpose();
    My.noalias() += wy[k] * pv * pv.transpose();
  }
  // p and its derivatives at the evaluation point (the origin of the shifted basis; d/dx = (1/s) d/dxi).
  VecL p(l), px(l), py(l);
  basis_.eval(0.0, 0.0, p.data(), px.data(), py.data());
  px /= s;
  py /= s;
  if (fe) {  // right-hand side p - S (2.87) and its derivatives
    for (int i = 0; i < fe->n; ++i) {
      VecL pi(l);
      const Vec2 d = (fe->x[i] - x) / s;
      basis_.eval(d.x(), d.y(), pi.data(), nullptr, nullptr);
      p -= fe->N[i] * pi;
      px -= fe->Nx[i] * pi;
      py -= fe->Ny[i] * pi;
    }
  }
  // Conditioning: eigenvalues of the symmetric M (l <= 9: cheap and exact).
  Eigen::SelfAdjointEigenSolver<MatL> eig(M);
  const double lmax = eig.eigenvalues().cwiseAbs().maxCoeff(), lmin = eig.eigenvalues().minCoeff();
  out.rcond = lmax > 0 ? lmin / lmax : 0.0;
  VecL g(l), gx(l), gy(l);
  if (out.rcond >= rcond_min_) {
    Eigen::LDLT<MatL> ldlt(M);
    g = ldlt.solve(p);
    gx = ldlt.solve(px - Mx * g);
    gy = ldlt.solve(py - My * g);
  } else {
    // Singular: the pseudo-inverse, accepted only if every right-hand side lies in the range of M (then the
    // functions still reproduce the basis and its derivatives).
    VecL inv = eig.eigenvalues();
    for (int i = 0; i < l; ++i) inv[i] = std::abs(inv[i]) > 1e-10 * lmax ? 1.0 / inv[i] : 0.0;
    const MatL Mp = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
    g = Mp * p;
    const VecL rx = px - Mx * g, ry = py - My * g;
    gx = Mp * rx;
    gy = Mp * ry;
    double e = (M * g - p).norm() / std::max(1.0, p.norm());
    if (derivatives)
      e += (M * gx - rx).norm() / std::max(1.0, rx.norm()) + (M * gy - ry).norm() / std::max(1.0, ry.norm());
    if (!(e < 1e-8)) {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    ": ill-conditioned moment matrix (reciprocal condition %.3g < %.3g) with %d support nodes for a "
                    "%d-term basis (degenerate node layout or too small a domain: enlarge alpha)",
                    out.rcond, rcond_min_, n, l);
      throw SolverError(where_text(x, where) + buf);
    }
  }
  out.N.resize(n);
  out.Nx.resize(n);
  out.Ny.resize(n);
  for (int k = 0; k < n; ++k) {
    Eigen::Map<const VecL> pk(&P[static_cast<size_t>(k) * l], l);
    const double gp = g.dot(pk);
    out.N[k] = gp * w[k];
    out.Nx[k] = gx.dot(pk) * w[k] + gp * wx[k];
    out.Ny[k] = gy.dot(pk) * w[k] + gp * wy[k];
  }
}

}  // namespace lagfsi::efg
