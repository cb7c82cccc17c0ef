// Mohr-Coulomb plasticity of the MPM particles (src/mpm/include/lagfsi/mpm/mpm_material.hpp): the return mapping of
// an elastic trial stress in principal stresses (tension positive, s1 >= s2 >= s3),
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi),   g = (s1 - s3) + (s1 + s3) sin(psi),
// onto the main plane, an edge (two planes active: s1 = s2 or s2 = s3) or the apex c cot(phi), then a tension
// cut-off (a Rankine cap below the apex); the stress returns along D : dg/dsigma (non-associated for psi < phi)
// and keeps the trial's principal directions.
#include <lagfsi/mpm/mpm_material.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace lagfsi::mpm {

namespace {
using Vec3 = Eigen::Vector3d;
}  // namespace

MohrCoulomb::MohrCoulomb(double young, double poisson, double density, double cohesion, double friction_angle,
                         double dilatancy_angle, double tension_cutoff)
    : MpmMaterial(young, poisson, density), cohesion_(cohesion) {
  sin_phi_ = std::sin(friction_angle * M_PI / 180);
  cos_phi_ = std::cos(friction_angle * M_PI / 180);
  sin_psi_ = std::sin(dilatancy_angle * M_PI / 180);
  tension_cutoff_ = tension_cutoff >= 0 ? tension_cutoff : cohesion_ * cos_phi_ / sin_phi_;
}

double MohrCoulomb::return_mapping(Stress& s) const {
  // Principal stresses (tension positive): the in-plane pair from the 2 x 2 block, and sigma_zz.
  const double c = 0.5 * (s[0] + s[1]), r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
  const double theta = 0.5 * std::atan2(2 * s[2], s[0] - s[1]);  // direction of the larger in-plane value
  std::array<double, 3> sp = {c + r, c - r, s[3]};               // in-plane max, in-plane min, zz
  std::array<int, 3> order = {0, 1, 2};                          // indices of s1 >= s2 >= s3
  std::sort(order.begin(), order.end(), [&](int a, int b) { return sp[a] > sp[b]; });
  Vec3 sig(sp[order[0]], sp[order[1]], sp[order[2]]);
  const double k = 2 * cohesion_ * cos_phi_;
  auto f_main = [&](const Vec3& x) { return (x[0] - x[2]) + (x[0] + x[2]) * sin_phi_ - k; };
  const double f0 = f_main(sig);
  const bool yields = f0 > 1e-12 * (std::abs(sig[0]) + std::abs(sig[2]) + k);
  if (!yields && sig[0] <= tension_cutoff_) return 0.0;
  // Yield normal m and flow direction n of a plane through (i, j) (i the largest, j the smallest principal).
  auto plane = [&](int i, int j, Vec3& m, Vec3& n) {
    m.setZero();
    n.setZero();
    m[i] = 1 + sin_phi_;
    m[j] = -(1 - sin_phi_);
    n[i] = 1 + sin_psi_;
    n[j] = -(1 - sin_psi_);
  };
  auto D = [&](const Vec3& n) -> Vec3 { return Vec3::Constant(lambda_ * n.sum()) + 2 * mu_ * n; };
  const double apex = sin_phi_ > 0 ? cohesion_ * cos_phi_ / sin_phi_ : 0.0;  // mean stress at the apex
  Vec3 m1, n1;
  plane(0, 2, m1, n1);
  const Vec3 Dn1 = D(n1);
  double dgamma = yields ? f0 / m1.dot(Dn1) : 0.0;
  Vec3 out = sig - dgamma * Dn1;
  if (yields && !(out[0] >= out[1] && out[1] >= out[2])) {
    // The return left the sextant: two planes are active (an edge), s1 = s2 or s2 = s3 at the end.
    Vec3 m2, n2;
    if (out[1] > out[0])
      plane(1, 2, m2, n2);  // edge s1 = s2: planes (1, 3) and (2, 3)
    else
      plane(0, 1, m2, n2);  // edge s2 = s3: planes (1, 3) and (1, 2)
    const Vec3 Dn2 = D(n2);
    const double f2 = m2.dot(sig) - k;
    const double a11 = m1.dot(Dn1), a12 = m1.dot(Dn2), a21 = m2.dot(Dn1), a22 = m2.dot(Dn2);
    const double det = a11 * a22 - a12 * a21;
    const double g1 = (a22 * f0 - a12 * f2) / det, g2 = (a11 * f2 - a21 * f0) / det;
    out = sig - g1 * Dn1 - g2 * Dn2;
    dgamma = g1 + g2;
    if (!(g1 >= 0 && g2 >= 0)) dgamma = -1;  // no admissible edge return: the apex below
  }
  // Beyond the apex (tension past c cot(phi), or an edge return with a negative multiplier): the apex.
  if (yields && (out.sum() / 3 > apex || out[0] > apex + 1e-9 * (std::abs(apex) + 1) || !(dgamma >= 0))) {
    out = Vec3::Constant(apex);
    dgamma = std::max(dgamma, 0.0) + (sig - out).norm() / (2 * mu_);
  }
  // Tension cut-off (a Rankine cap below the apex): no principal stress above it.
  for (int a = 0; a < 3; ++a)
    if (out[a] > tension_cutoff_) {
      dgamma += (out[a] - tension_cutoff_) / (2 * mu_);
      out[a] = tension_cutoff_;
    }
  // Back to (xx, yy, xy, zz) with the trial's principal directions.
  std::array<double, 3> back{};
  for (int a = 0; a < 3; ++a) back[order[a]] = out[a];
  const double cc = 0.5 * (back[0] + back[1]), rr = 0.5 * (back[0] - back[1]);
  s[0] = cc + rr * std::cos(2 * theta);
  s[1] = cc - rr * std::cos(2 * theta);
  s[2] = rr * std::sin(2 * theta);
  s[3] = back[2];
  return dgamma;
}

}  // namespace lagfsi::mpm
