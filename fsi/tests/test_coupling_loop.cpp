// Unit tests of the Dirichlet-Neumann loop (fsi/coupling.hpp) on the linear model of one implicit time step of a
// structure in an incompressible fluid (the added-mass problem of Causin, Gerbeau & Nobile 2005): the solid
// (stiffness K, mass Ms) under the interface force f, and the fluid that returns the inertial force of the mass
// it moves, f = -c Mf (x - x_p), c = 4/dt^2 (Newmark), x_p the predicted interface position. The monolithic step
// solves (K + c Ms + c Mf) x = g + c Mf x_p; the plain loop converges only if the added mass is small
// against the structure's (|c Mf (K + c Ms)^-1| < 1).
#include <gtest/gtest.h>

#include <lagfsi/fsi/coupling.hpp>

#include <Eigen/Dense>
#include <cstdio>
#include <random>

namespace {

using lagfsi::Json;
using lagfsi::Params;
using lagfsi::Vec;
using namespace lagfsi::fsi;

struct Piston {
  Eigen::MatrixXd K, Ms, Mf;
  Vec g, xp;
  double c = 4.0 / (1e-3 * 1e-3);
  int fluid_calls = 0, solid_calls = 0;

  /// n interface dofs; the fluid's added-mass matrix is a full SPD matrix of total mass ratio `ratio`.
  Piston(int n, double ratio) {
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {  // a chain of springs
      K(i, i) += 2e4;
      if (i + 1 < n) K(i, i + 1) = K(i + 1, i) = -1e4;
    }
    Ms = Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = u(gen) / n;
    Mf = ratio * (A * A.transpose() + Eigen::MatrixXd::Identity(n, n)) / 2.0;
    g = Vec::LinSpaced(n, 1.0, 2.0);
    xp = Vec::Constant(n, 1e-3);
  }
  Vec fluid(const Vec& x) {
    ++fluid_calls;
    return -c * Mf * (x - xp);
  }
  Vec solid(const Vec& f) {
    ++solid_calls;
    return (K + c * Ms).ldlt().solve(g + f);
  }
  Vec monolithic() const { return (K + c * Ms + c * Mf).ldlt().solve(g + c * Mf * xp); }
};

CouplingReport run(Piston& p, const Json& acc, Vec& x, int max_it = 100) {
  auto a = make_acceleration(Params(acc, "test"));
  CouplingSettings s;
  s.max_iterations = max_it;
  s.tolerance = 1e-8;
  x = p.xp;
  return dirichlet_neumann_step([&](const Vec& xi) { return p.fluid(xi); }, [&](const Vec& f) { return p.solid(f); },
                                *a, x, s);
}

TEST(CouplingLoop, LightFluidConvergesWithoutAcceleration) {
  Piston p(10, 0.1);
  Vec x;
  const auto r = run(p, {{"type", "constant"}, {"relaxation", 1.0}}, x);
  ASSERT_TRUE(r.converged) << r.iterations;
  EXPECT_LT((x - p.monolithic()).norm(), 1e-6 * (p.monolithic() - p.xp).norm());
  EXPECT_EQ(p.fluid_calls, r.iterations);
  EXPECT_EQ(p.solid_calls, r.iterations);
}

TEST(CouplingLoop, HeavyFluidNeedsAcceleration) {
  // Mass ratio 10: the plain and the under-relaxed loops do not converge; Aitken and IQN-ILS do, to the
  // monolithic solution.
  Vec x;
  Piston p0(10, 10.0);
  const auto plain = run(p0, {{"type", "constant"}, {"relaxation", 1.0}}, x);
  EXPECT_FALSE(plain.converged);
  Piston p1(10, 10.0);
  const auto relaxed = run(p1, {{"type", "constant"}, {"relaxation", 0.5}}, x);
  EXPECT_FALSE(relaxed.converged);
  Piston p2(10, 10.0);
  const auto aitken = run(p2, {{"type", "aitken"}, {"initial_relaxation", 0.05}}, x);
  ASSERT_TRUE(aitken.converged);
  EXPECT_LT((x - p2.monolithic()).norm(), 1e-6 * (p2.monolithic() - p2.xp).norm());
  Piston p3(10, 10.0);
  const auto iqn = run(p3, {{"type", "iqn_ils"}, {"initial_relaxation", 0.05}, {"reuse_steps", 0}}, x);
  ASSERT_TRUE(iqn.converged);
  EXPECT_LT((x - p3.monolithic()).norm(), 1e-6 * (p3.monolithic() - p3.xp).norm());
  EXPECT_LE(iqn.iterations, aitken.iterations);
  std::printf(
      "mass ratio 10: Aitken %d iterations, IQN-ILS %d; plain and w = 0.5 not converged in 100 (last "
      "residual/reference %.2e, %.2e)\n",
      aitken.iterations, iqn.iterations, plain.residual / plain.reference, relaxed.residual / relaxed.reference);
}

TEST(CouplingLoop, ReportsNonConvergenceWithoutThrowing) {
  Piston p(4, 50.0);
  Vec x;
  CouplingReport r;
  EXPECT_NO_THROW(r = run(p, {{"type", "constant"}, {"relaxation", 1.0}}, x, 20));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 20);
}

}  // namespace
