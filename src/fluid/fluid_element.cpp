#include <lagfsi/fluid/fluid_element.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lagfsi {

namespace {

/// pspg_element, with the tangent (Tangent) or without it (K is not touched): the residual's operations are the same
/// either way.
template <bool Tangent>
bool element(const PspgElementInput& in, Eigen::Matrix<double, 9, 1>& r, Eigen::Matrix<double, 9, 9>& K,
             double& inertia2, double& gravity2, double* viscous2) {
  const double A2 =
      (in.x[1] - in.x[0]).x() * (in.x[2] - in.x[0]).y() - (in.x[1] - in.x[0]).y() * (in.x[2] - in.x[0]).x();
  if (!(A2 > 0.0)) return false;
  const double nu = in.rho > 0 ? in.mu / in.rho : 0.0;
  const double A = 0.5 * A2;
  Vec2 dN[3];
  for (int k = 0; k < 3; ++k) {
    const Vec2& b = in.x[(k + 1) % 3];
    const Vec2& c = in.x[(k + 2) % 3];
    dN[k] = Vec2(b.y() - c.y(), c.x() - b.x()) / A2;
  }
  // Stabilization parameter.
  const double he = 2.0 * std::sqrt(A / std::numbers::pi);
  const Vec2 vmean = (in.v[0] + in.v[1] + in.v[2]) / 3.0;
  double tau;
  if (in.tau_U <= 0) {
    const double s =
        std::pow(2.0 / in.dt, 2) + std::pow(2.0 * vmean.norm() / he, 2) + std::pow(4.0 * nu / (he * he), 2);
    tau = 1.0 / std::sqrt(s);
  } else {
    const double Re = in.tau_U * he / (2.0 * std::max(nu, 1e-300));
    tau = he / (2.0 * in.tau_U) * std::min(Re / 3.0, 1.0);
  }
  // Kinematics of the element.
  Mat2 L = Mat2::Zero();  // velocity gradient
  Vec2 gradp = Vec2::Zero();
  double pmean = 0;
  for (int k = 0; k < 3; ++k) {
    L += in.v[k] * dN[k].transpose();
    gradp += in.p[k] * dN[k];
    pmean += in.p[k] / 3.0;
  }
  const Mat2 sym2 = L + L.transpose();  // 2 * strain rate
  const double divv = L.trace();
  const Vec2 amean = (in.a[0] + in.a[1] + in.a[2]) / 3.0;
  const double m = in.rho * A / 3.0;

  r.setZero();
  if constexpr (Tangent) K.setZero();
  for (int a = 0; a < 3; ++a) {
    // momentum
    Vec2 inertia;
    if (in.lumped) {
      inertia = m * in.a[a];
    } else {
      inertia = in.rho * A / 12.0 * (in.a[0] + in.a[1] + in.a[2] + in.a[a]);
    }
    const Vec2 visc = in.mu * A * sym2 * dN[a];
    const Vec2 pres = -A * pmean * dN[a];
    const Vec2 grav = -m * in.g;
    r.segment<2>(3 * a) = inertia + visc + pres + grav;
    inertia2 += inertia.squaredNorm();
    gravity2 += grav.squaredNorm();
    if (viscous2) *viscous2 += visc.squaredNorm();
    // continuity
    r[3 * a + 2] =
        A / 3.0 * (divv + in.c_vol) + tau * A * dN[a].dot(amean - in.g) + tau / in.rho * A * dN[a].dot(gradp);
    // Slight compressibility, (1/K) dp/dt (lumped): physical for water (K = 2.2 GPa) and it makes the
    // pressure of a fluid pocket without free surface (a corner filled by a wave, a trapped region)
    // determined instead of leaving a singular constant mode.
    if (in.bulk > 0) {
      r[3 * a + 2] += A / 3.0 * (in.p[a] - in.p_old[a]) / (in.bulk * in.dt);
      if constexpr (Tangent) K(3 * a + 2, 3 * a + 2) += A / 3.0 / (in.bulk * in.dt);
    }
    if constexpr (!Tangent) continue;
    for (int b = 0; b < 3; ++b) {
      // d(momentum_a)/d(x_b): mass and viscous terms
      const double mass_ab = in.lumped ? (a == b ? m : 0.0) : in.rho * A / 12.0 * (a == b ? 2.0 : 1.0);
      const double dd = dN[a].dot(dN[b]);
      Mat2 Kv = in.mu * A * (dd * Mat2::Identity() + dN[b] * dN[a].transpose());
      K.block<2, 2>(3 * a, 3 * b) += in.c_m * mass_ab * Mat2::Identity() + in.c_c * Kv;
      // d(momentum_a)/d(p_b)
      K.block<2, 1>(3 * a, 3 * b + 2) += -A / 3.0 * dN[a];
      // d(continuity_a)/d(x_b)
      K.block<1, 2>(3 * a + 2, 3 * b) += (in.c_c * A / 3.0 * dN[b] + in.c_m * tau * A / 3.0 * dN[a]).transpose();
      // d(continuity_a)/d(p_b)
      K(3 * a + 2, 3 * b + 2) += tau / in.rho * A * dd;
    }
  }
  // The free surface's Robin condition (fluid_element.hpp): beta (p_a - 2 mu n.L.n) on each free edge's ends.
  for (int k = 0; k < 3; ++k) {
    if (!(in.robin_edges & (1u << k)) || in.robin_factor <= 0) continue;
    const int k1 = (k + 1) % 3;
    const Vec2 e = in.x[k1] - in.x[k];
    const double len2 = e.squaredNorm();
    const Vec2 n = Vec2(e.y(), -e.x()) / std::sqrt(len2);            // outward for a counter-clockwise element
    const double beta = in.robin_factor * tau / in.rho * len2 / A2;  // f (tau/rho)(2/h_n)(L/2), h_n = 2A/L
    const double snn = 2.0 * in.mu * n.dot(L * n);                   // normal viscous stress
    for (const int a : {k, k1}) {
      r[3 * a + 2] += beta * (in.p[a] - snn);
      if constexpr (!Tangent) continue;
      K(3 * a + 2, 3 * a + 2) += beta;
      for (int b = 0; b < 3; ++b)
        K.block<1, 2>(3 * a + 2, 3 * b) += (-beta * 2.0 * in.mu * in.c_c * n.dot(dN[b]) * n).transpose();
    }
  }
  return true;
}

}  // namespace

bool pspg_element(const PspgElementInput& in, Eigen::Matrix<double, 9, 1>& r, Eigen::Matrix<double, 9, 9>& K,
                  double& inertia2, double& gravity2, double* viscous2) {
  return element<true>(in, r, K, inertia2, gravity2, viscous2);
}

bool pspg_residual(const PspgElementInput& in, Eigen::Matrix<double, 9, 1>& r, double& inertia2, double& gravity2,
                   double* viscous2) {
  Eigen::Matrix<double, 9, 9> unused;
  return element<false>(in, r, unused, inertia2, gravity2, viscous2);
}

}  // namespace lagfsi
