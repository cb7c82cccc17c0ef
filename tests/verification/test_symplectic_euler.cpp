// Symplectic Euler (src/core/include/lagfsi/time_integrator.hpp), the family's member for the models whose new
// velocity comes before the new position, on the undamped oscillator: bounded energy and first order.
#include <lagfsi/time_integrator.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace {
/// The undamped oscillator x'' = -x from x = 1, v = 0 over `periods` periods with symplectic Euler's
/// explicit_step: the largest |energy - 1/2| on the way, and the final error in x.
std::pair<double, double> symplectic_euler_oscillator(double dt, int periods) {
  auto integrator = lagfsi::make_symplectic_euler();
  lagfsi::KinematicState s;
  s.x = lagfsi::Vec::Ones(1);
  s.v = lagfsi::Vec::Zero(1);
  s.a = lagfsi::Vec::Zero(1);
  const lagfsi::Vec inv_mass = lagfsi::Vec::Ones(1);
  const double T = 2 * std::numbers::pi * periods;
  const long n = std::lround(T / dt);
  double energy_error = 0;
  for (long k = 0; k < n; ++k) {
    integrator->explicit_step([](const lagfsi::Vec& x, const lagfsi::Vec&, double) { return lagfsi::Vec(-x); },
                              inv_mass, T / n, s);
    energy_error = std::max(energy_error, std::abs(0.5 * (s.x[0] * s.x[0] + s.v[0] * s.v[0]) - 0.5));
  }
  return {energy_error, std::abs(s.x[0] - 1.0)};
}
}  // namespace

TEST(SymplecticEuler, KeepsTheOscillatorsEnergyBoundedAndConvergesAtFirstOrder) {
  // Symplectic: over 100 periods the energy oscillates within O(dt) of its value, with no drift.
  EXPECT_LT(symplectic_euler_oscillator(0.02, 100).first, 0.02);
  // First order: halving dt halves the energy error (the central difference, second order, would quarter it).
  const double ea = symplectic_euler_oscillator(0.01, 1).first, eb = symplectic_euler_oscillator(0.005, 1).first;
  EXPECT_NEAR(ea / eb, 2.0, 0.2);
}
