#pragma once
// Central finite differences for tangent checks: the Jacobian of a vector function and the gradient of a
// scalar one, column by column (error O(h^2) truncation + O(eps |f| / h) round-off).
#include <Eigen/Dense>

namespace lagfsi::testing {

/// J_ij = (f_i(x + h e_j) - f_i(x - h e_j)) / (2 h); f(x, out) writes f(x) into out.
template <class VectorFunction>
Eigen::MatrixXd central_jacobian(VectorFunction f, const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd fp, fm;
  Eigen::MatrixXd J;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    f(xp, fp);
    f(xm, fm);
    if (j == 0) J.resize(fp.size(), x.size());
    J.col(j) = (fp - fm) / (2.0 * h);
  }
  return J;
}

/// g_j = (W(x + h e_j) - W(x - h e_j)) / (2 h).
template <class ScalarFunction>
Eigen::VectorXd central_gradient(ScalarFunction W, const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    g[j] = (W(xp) - W(xm)) / (2.0 * h);
  }
  return g;
}

}  // namespace lagfsi::testing
