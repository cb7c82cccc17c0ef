// What the MPM schemes share (mpm_scheme.hpp): the explicit sub-stepping and the particles' linear elastic
// small-strain update from a displacement increment.
//
// Time: the driver's step is split into sub-steps dt_sub <= cfl h / c, c = sqrt((lambda + 2 mu)/rho) the
// P-wave speed (explicit, conditionally stable; with water, c includes K_w / n). The grid is reset every
// sub-step.
#include "mpm_scheme.hpp"

#include <algorithm>
#include <cmath>

namespace lagfsi::mpm {

int ExplicitScheme::advance(MpmBody& b, double t_new, double dt_step) {
  const double c = wave_speed(b);
  const double dt_max = b.cfl * b.grid.h / c;
  const int n = std::max(1, static_cast<int>(std::ceil(dt_step / dt_max * (1 - 1e-12))));
  const double dt = dt_step / n;
  for (int k = 0; k < n; ++k) {
    substep(b, dt);
    b.t += dt;
  }
  b.t = t_new;
  return n;
}

void elastic_increment(Particles& P, Index q, const Mat2& G, const MpmMaterial& mat) {
  const double dxx = G(0, 0), dyy = G(1, 1), dxy = 0.5 * (G(0, 1) + G(1, 0));
  mat.add_elastic_increment(P.stress[q], dxx, dyy, dxy);
  auto& e = P.strain[q];
  e[0] += dxx;
  e[1] += dyy;
  e[2] += dxy;
  P.F[q] = (Mat2::Identity() + G) * P.F[q];
  const Mat2& F = P.F[q];
  P.volume[q] = (F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0)) * P.volume0[q];
}

}  // namespace lagfsi::mpm
