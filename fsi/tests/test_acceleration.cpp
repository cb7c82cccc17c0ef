// Unit tests of the coupling accelerators (fsi/): on a linear model of a Dirichlet-Neumann pass with a strong
// added-mass effect, H(x) = b - M x with M symmetric positive definite and eigenvalues up to 3, the plain
// iteration x <- H(x) diverges (the interface "overshoots" as for a light structure in a heavy fluid); the
// fixed point solves (I + M) x = b.
#include <gtest/gtest.h>

#include <lagfsi/error.hpp>
#include <lagfsi/fsi/acceleration.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

using lagfsi::Json;
using lagfsi::Params;
using lagfsi::Vec;
using lagfsi::fsi::make_acceleration;

struct Model {
  Eigen::MatrixXd M;
  Vec b;
  Vec solution() const { return (Eigen::MatrixXd::Identity(M.rows(), M.cols()) + M).ldlt().solve(b); }
  Vec pass(const Vec& x) const { return b - M * x; }
};

/// M = Q diag(lambda) Q^T with lambda spread over [lo, hi] and a random orthogonal Q (fixed seed).
Model make_model(int n, double lo, double hi, unsigned seed = 7) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> nd;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = nd(gen);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  Vec lam(n);
  for (int i = 0; i < n; ++i) lam[i] = lo + (hi - lo) * i / (n - 1);
  Model m;
  m.M = Q * lam.asDiagonal() * Q.transpose();
  m.b = Vec::Ones(n);
  return m;
}

/// Iterations until |r| <= tol |r_0| (or -1 within max_it); the last iterate in x.
int iterate(lagfsi::fsi::Acceleration& acc, const Model& m, Vec& x, double tol, int max_it) {
  acc.begin_step();
  const double r0 = (m.pass(x) - x).norm();
  for (int k = 1; k <= max_it; ++k) {
    const Vec xt = m.pass(x);
    if ((xt - x).norm() <= tol * r0) {
      acc.end_step();
      return k - 1;
    }
    x = acc.update(x, xt);
    if (!x.allFinite() || (xt - x).norm() > 1e12 * r0) return -1;
  }
  return -1;
}

std::unique_ptr<lagfsi::fsi::Acceleration> make(const Json& j) { return make_acceleration(Params(j, "test")); }

TEST(Acceleration, ConstantRelaxationConvergesOnlyWhenSmallEnough) {
  const Model m = make_model(20, 0.1, 3.0);
  // x <- x + w (H(x) - x) has the iteration matrix I - w (I + M): converges iff w < 2 / (1 + 3) = 0.5.
  Vec x = Vec::Zero(20);
  auto small = make({{"type", "constant"}, {"relaxation", 0.3}});
  const int k = iterate(*small, m, x, 1e-8, 1000);
  EXPECT_GT(k, 0);
  EXPECT_LT((x - m.solution()).norm(), 1e-6 * m.solution().norm());
  x = Vec::Zero(20);
  auto large = make({{"type", "constant"}, {"relaxation", 0.7}});
  EXPECT_EQ(iterate(*large, m, x, 1e-8, 300), -1) << "w = 0.7 must diverge";
}

TEST(Acceleration, AitkenBeatsTheBestFixedRelaxation) {
  const Model m = make_model(20, 0.1, 3.0);
  Vec x = Vec::Zero(20);
  auto fixed = make({{"type", "constant"}, {"relaxation", 0.3}});
  const int k_fixed = iterate(*fixed, m, x, 1e-8, 1000);
  x = Vec::Zero(20);
  auto aitken = make({{"type", "aitken"}, {"initial_relaxation", 0.3}});
  const int k_aitken = iterate(*aitken, m, x, 1e-8, 1000);
  ASSERT_GT(k_aitken, 0);
  EXPECT_LT(k_aitken, k_fixed) << "Aitken " << k_aitken << " vs fixed " << k_fixed;
  std::printf("iterations to 1e-8: constant 0.3 %d, Aitken %d\n", k_fixed, k_aitken);
  EXPECT_LT((x - m.solution()).norm(), 1e-6 * m.solution().norm());
}

TEST(Acceleration, IqnIlsSolvesALinearProblemInAboutNIterations) {
  // On a linear H, the least-squares model becomes exact once it has n independent columns.
  const int n = 20;
  const Model m = make_model(n, 0.1, 3.0);
  Vec x = Vec::Zero(n);
  auto iqn = make({{"type", "iqn_ils"}, {"initial_relaxation", 0.1}, {"reuse_steps", 0}});
  const int k = iterate(*iqn, m, x, 1e-10, 200);
  ASSERT_GT(k, 0);
  EXPECT_LE(k, n + 2);
  std::printf("IQN-ILS iterations to 1e-10 on n = %d: %d\n", n, k);
  EXPECT_LT((x - m.solution()).norm(), 1e-8 * m.solution().norm());
}

TEST(Acceleration, IqnIlsReuseSavesIterationsOverSteps) {
  // Ten "time steps" of the same interface operator with a slowly changing right-hand side: with the
  // columns of earlier steps the model is nearly complete from the first iteration of a step.
  const int n = 40;
  Model m = make_model(n, 0.1, 3.0);
  auto total = [&](int reuse) {
    auto acc = make({{"type", "iqn_ils"}, {"initial_relaxation", 0.1}, {"reuse_steps", reuse}});
    Model mm = m;
    Vec x = Vec::Zero(n);
    int sum = 0;
    for (int s = 0; s < 10; ++s) {
      for (int i = 0; i < n; ++i) mm.b[i] = 1.0 + 0.1 * std::sin(0.3 * s + 0.2 * i);
      const int k = iterate(*acc, mm, x, 1e-8, 500);
      EXPECT_GT(k, 0) << "reuse " << reuse << " step " << s;
      sum += k;
    }
    return sum;
  };
  const int without = total(0), with = total(8);
  EXPECT_LT(with, 0.6 * without) << "with reuse " << with << ", without " << without;
  std::printf("IQN-ILS over 10 steps: %d iterations without reuse, %d with 8 steps reused\n", without, with);
}

TEST(Acceleration, IqnIlsFilterKeepsTheModelSolvable) {
  // A 3-dimensional problem iterated far past convergence in exact arithmetic: later columns are dependent
  // on earlier ones, and reused steps repeat them; without the filter the triangular solve would divide by
  // round-off. The iteration must stay finite and converged.
  const Model m = make_model(3, 0.5, 2.5);
  auto acc = make({{"type", "iqn_ils"}, {"initial_relaxation", 0.2}, {"reuse_steps", 20}, {"filter", 1e-6}});
  Vec x = Vec::Zero(3);
  for (int s = 0; s < 5; ++s) {
    acc->begin_step();
    for (int k = 0; k < 30; ++k) x = acc->update(x, m.pass(x));
    acc->end_step();
    ASSERT_TRUE(x.allFinite());
    EXPECT_LE(acc->model_columns(), 3);
  }
  EXPECT_LT((x - m.solution()).norm(), 1e-8 * m.solution().norm());
}

TEST(Acceleration, IqnImvjLearnsTheInverseJacobianAcrossSteps) {
  // The same ten steps as above. IMVJ's first step is ILS without reuse; its Jacobian, corrected by every
  // step's columns, becomes the exact inverse Jacobian of the residual map once the steps have spanned the
  // space, after which a step needs about three iterations. On this fixed linear operator ILS with reuse
  // does as well (its old columns never go stale); IMVJ's gain in the FSI cases is that it has no columns
  // to go stale when the contact state changes (README of elastic_obstacle_walhorn).
  const int n = 40;
  Model m = make_model(n, 0.1, 3.0);
  auto run = [&](const Json& j, int steps, std::vector<int>* per_step) {
    auto acc = make(j);
    Model mm = m;
    Vec x = Vec::Zero(n);
    int sum = 0;
    for (int s = 0; s < steps; ++s) {
      for (int i = 0; i < n; ++i) mm.b[i] = 1.0 + 0.1 * std::sin(0.3 * s + 0.2 * i);
      const int k = iterate(*acc, mm, x, 1e-8, 500);
      EXPECT_GT(k, 0) << j.dump() << " step " << s;
      EXPECT_LT((x - mm.solution()).norm(), 1e-6 * mm.solution().norm()) << j.dump() << " step " << s;
      if (per_step) per_step->push_back(k);
      sum += k;
    }
    return sum;
  };
  std::vector<int> imvj_steps;
  const int ils0 = run({{"type", "iqn_ils"}, {"reuse_steps", 0}}, 10, nullptr);
  const int ils8 = run({{"type", "iqn_ils"}, {"reuse_steps", 8}}, 10, nullptr);
  const int imvj = run({{"type", "iqn_imvj"}}, 10, &imvj_steps);
  std::printf("over 10 steps: ILS %d, ILS reusing 8 steps %d, IMVJ %d iterations (IMVJ per step:", ils0, ils8, imvj);
  for (int k : imvj_steps) std::printf(" %d", k);
  std::printf(")\n");
  EXPECT_LT(imvj, ils0 / 2);
  EXPECT_LT(imvj, 1.5 * ils8);
  EXPECT_LE(imvj_steps.back(), 3);  // the Jacobian has been learnt
  EXPECT_EQ(imvj_steps.front(), run({{"type", "iqn_ils"}, {"reuse_steps", 0}}, 1, nullptr));  // step 1 is ILS
}

TEST(Acceleration, IqnImvjResetForgetsTheJacobian) {
  const int n = 10;
  const Model m = make_model(n, 0.1, 3.0);
  auto acc = make({{"type", "iqn_imvj"}, {"initial_relaxation", 0.3}});
  Vec x = Vec::Zero(n);
  ASSERT_GT(iterate(*acc, m, x, 1e-10, 200), 0);
  // With a learnt Jacobian the first update from a fresh start jumps close to the solution; after reset()
  // it is a plain relaxation x + w r again.
  acc->reset();
  acc->begin_step();
  const Vec x0 = Vec::Zero(n);
  const Vec x1 = acc->update(x0, m.pass(x0));
  EXPECT_LT((x1 - 0.3 * m.pass(x0)).norm(), 1e-14);
}

TEST(Acceleration, BadParametersAreInputErrors) {
  EXPECT_THROW(make({{"type", "iqn_imvj"}, {"reuse_steps", 2}}), lagfsi::InputError);  // IMVJ keeps a Jacobian
  EXPECT_THROW(make({{"type", "broyden"}}), lagfsi::InputError);
  EXPECT_THROW(make({{"type", "constant"}, {"relaxation", 1.5}}), lagfsi::InputError);
  EXPECT_THROW(make({{"type", "aitken"}, {"omega", 0.5}}), lagfsi::InputError);
  EXPECT_THROW(make({{"type", "iqn_ils"}, {"reuse_steps", -1}}), lagfsi::InputError);
  EXPECT_THROW(make({{"type", "iqn_ils"}, {"filter", 2.0}}), lagfsi::InputError);
  EXPECT_THROW(make(Json::object()), lagfsi::InputError);
}

}  // namespace
