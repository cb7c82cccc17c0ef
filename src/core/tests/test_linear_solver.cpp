// Unit tests of the sparse direct solvers (linear_solver.hpp): accuracy on SPD and unsymmetric systems,
// symbolic-analysis reuse, and the SolverError / invalid_argument contract.
#include <lagfsi/error.hpp>
#include <lagfsi/linear_solver.hpp>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "test_systems.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace lagfsi;
using lagfsi::testing::laplacian;
using lagfsi::testing::random_vector;

namespace {

// Upwind convection-diffusion on an n x n grid: same pattern as the Laplacian, unsymmetric values.
SparseMatrix convection_diffusion(int n, double peclet) {
  std::vector<Triplet> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + 2.0 * peclet);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0 - peclet);
      if (i < n - 1) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0 - peclet);
      if (j < n - 1) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  SparseMatrix A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double relative_residual(const SparseMatrix& A, const Vec& x, const Vec& b) { return (A * x - b).norm() / b.norm(); }

SparseMatrix from_dense(const Eigen::MatrixXd& D) {
  SparseMatrix A = D.sparseView(0.0, 0.0);  // keeps only non-zero entries
  A.makeCompressed();
  return A;
}

// Solves with a fresh solver of `type` and returns the relative residual.
double solve_residual(const std::string& type, const SparseMatrix& A_given, const SparseMatrix& A_full, unsigned seed) {
  auto solver = make_linear_solver(type);
  solver->setup(A_given);
  const Vec b = random_vector(A_full.rows(), seed);
  Vec x;
  solver->solve(b, x);
  return relative_residual(A_full, x, b);
}

const std::vector<std::string> kAll{"cholmod",  "cholmod_supernodal", "umfpack", "klu",
                                    "eigen_lu", "eigen_ldlt",         "mumps"};
const std::vector<std::string> kSymmetric{"cholmod", "cholmod_supernodal", "eigen_ldlt"};
const std::vector<std::string> kLU{"umfpack", "klu", "eigen_lu", "mumps"};

}  // namespace

class EverySolver : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(LinearSolver, EverySolver, ::testing::ValuesIn(kAll),
                         [](const auto& info) { return info.param; });

TEST_P(EverySolver, TypeStringRoundTrips) {
  auto solver = make_linear_solver(GetParam());
  EXPECT_EQ(solver->type(), GetParam());
  EXPECT_EQ(solver->symmetric_only(),
            GetParam() == "cholmod" || GetParam() == "cholmod_supernodal" || GetParam() == "eigen_ldlt");
  EXPECT_EQ(solver->symbolic_analyses(), 0);
}

TEST_P(EverySolver, SolvesShiftedLaplacian) {
  const SparseMatrix A = laplacian(30, 0.01);
  EXPECT_LT(solve_residual(GetParam(), A, A, 1), 1e-10);

  // Independent check of the solution itself: manufactured x, b = A x.
  auto solver = make_linear_solver(GetParam());
  solver->setup(A);
  const Vec x_exact = random_vector(A.rows(), 2);
  Vec x;
  solver->solve(A * x_exact, x);
  EXPECT_LT((x - x_exact).norm() / x_exact.norm(), 1e-8);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
}

TEST_P(EverySolver, ReusesAnalysisWhilePatternIsUnchanged) {
  auto solver = make_linear_solver(GetParam());
  const SparseMatrix A1 = laplacian(20, 0.5);
  solver->setup(A1);
  EXPECT_EQ(solver->symbolic_analyses(), 1);

  // Same pattern, different values: the new values must be used (check the solution), no new analysis.
  const SparseMatrix A2 = laplacian(20, 2.0);
  solver->setup(A2);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  const Vec b = random_vector(A2.rows(), 5);
  Vec x;
  solver->solve(b, x);
  EXPECT_LT(relative_residual(A2, x, b), 1e-10);

  // Same pattern given in uncompressed storage: still no new analysis.
  SparseMatrix A3 = laplacian(20, 1.0);
  A3.uncompress();
  ASSERT_FALSE(A3.isCompressed());
  solver->setup(A3);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  solver->solve(b, x);
  EXPECT_LT(relative_residual(A3, x, b), 1e-10);

  // Different pattern (same size, one extra symmetric pair of entries): a new analysis.
  SparseMatrix A4 = laplacian(20, 1.0);
  A4.coeffRef(0, 399) = -0.1;
  A4.coeffRef(399, 0) = -0.1;
  A4.makeCompressed();
  solver->setup(A4);
  EXPECT_EQ(solver->symbolic_analyses(), 2);
  solver->solve(b, x);
  EXPECT_LT(relative_residual(A4, x, b), 1e-10);

  // Different size: a new analysis.
  const SparseMatrix A5 = laplacian(15, 1.0);
  solver->setup(A5);
  EXPECT_EQ(solver->symbolic_analyses(), 3);
  const Vec b5 = random_vector(A5.rows(), 6);
  solver->solve(b5, x);
  EXPECT_LT(relative_residual(A5, x, b5), 1e-10);
}

TEST_P(EverySolver, SolveInPlace) {
  const SparseMatrix A = laplacian(10, 0.2);
  auto solver = make_linear_solver(GetParam());
  solver->setup(A);
  const Vec b = random_vector(A.rows(), 7);
  Vec x = b;
  solver->solve(x, x);
  EXPECT_LT(relative_residual(A, x, b), 1e-10);
}

TEST_P(EverySolver, EmptySystem) {
  auto solver = make_linear_solver(GetParam());
  solver->setup(SparseMatrix(0, 0));
  Vec x(3);
  solver->solve(Vec(0), x);
  EXPECT_EQ(x.size(), 0);
}

TEST_P(EverySolver, NumericallySingularMatrixThrows) {
  // Rows 0 and 1 are proportional: singular, symmetric, and every elimination gives an exact zero pivot.
  Eigen::MatrixXd D(3, 3);
  D << 1, 2, 0,  //
      2, 4, 0,   //
      0, 0, 1;
  auto solver = make_linear_solver(GetParam());
  try {
    solver->setup(from_dense(D));
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(GetParam() + ": ", 0), 0u) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
  // No solve with a failed factorization.
  Vec x;
  EXPECT_THROW(solver->solve(Vec::Ones(3), x), SolverError);
}

TEST_P(EverySolver, NonFiniteEntriesThrowAndSolverRecovers) {
  SparseMatrix A = laplacian(8, 0.1);
  auto solver = make_linear_solver(GetParam());
  solver->setup(A);
  SparseMatrix bad = A;
  bad.coeffRef(5, 5) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver->setup(bad), SolverError);
  bad.coeffRef(5, 5) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(solver->setup(bad), SolverError);
  Vec x;
  EXPECT_THROW(solver->solve(Vec::Ones(A.rows()), x), SolverError);
  // A valid matrix with the same pattern works again, without a new analysis.
  solver->setup(A);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  const Vec b = random_vector(A.rows(), 8);
  solver->solve(b, x);
  EXPECT_LT(relative_residual(A, x, b), 1e-10);
  // Non-finite right-hand side.
  Vec nan_b = b;
  nan_b[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver->solve(nan_b, x), SolverError);
}

TEST_P(EverySolver, MisuseThrows) {
  auto solver = make_linear_solver(GetParam());
  Vec x;
  EXPECT_THROW(solver->solve(Vec::Ones(4), x), SolverError);     // before factorize
  EXPECT_THROW(solver->setup(SparseMatrix(4, 5)), SolverError);  // not square
  solver->setup(laplacian(3, 0.1));
  EXPECT_THROW(solver->solve(Vec::Ones(4), x), SolverError);  // size mismatch
}

class SymmetricSolver : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(LinearSolver, SymmetricSolver, ::testing::ValuesIn(kSymmetric),
                         [](const auto& info) { return info.param; });

TEST_P(SymmetricSolver, ReadsOnlyTheLowerTriangle) {
  const SparseMatrix A = laplacian(12, 0.1);
  ASSERT_TRUE(make_linear_solver(GetParam())->symmetric_only());
  const SparseMatrix lower = A.triangularView<Eigen::Lower>();
  EXPECT_LT(solve_residual(GetParam(), lower, A, 3), 1e-10);
  // Garbage in the strict upper triangle must be ignored too.
  SparseMatrix garbage = A;
  for (int k = 0; k < garbage.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(garbage, k); it; ++it)
      if (it.row() < it.col()) it.valueRef() = 1e3;
  EXPECT_LT(solve_residual(GetParam(), garbage, A, 4), 1e-10);
}

class LUSolver : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(LinearSolver, LUSolver, ::testing::ValuesIn(kLU), [](const auto& info) { return info.param; });

TEST_P(LUSolver, SolvesUnsymmetricSystem) {
  const SparseMatrix A = convection_diffusion(30, 3.0);
  const SparseMatrix At = A.transpose();
  ASSERT_GT((A - At).norm(), 1.0);  // really unsymmetric
  EXPECT_LT(solve_residual(GetParam(), A, A, 9), 1e-10);
}

TEST_P(LUSolver, UnsymmetricDenseSmallSystemMatchesDenseLU) {
  // Independent reference: Eigen's dense partial-pivoting LU on the same 6x6 matrix.
  Eigen::MatrixXd D(6, 6);
  D << 0, 2, 0, 1, 0, 0,  //
      3, 0, 0, 0, 1, 0,   //
      0, 1, 5, 0, 0, 2,   //
      1, 0, 0, 0, 4, 0,   //
      0, 0, 2, 0, 0, 7,   //
      0, 3, 0, 6, 0, 1;
  const Vec b = random_vector(6, 10);
  const Vec x_ref = D.partialPivLu().solve(b);
  auto solver = make_linear_solver(GetParam());
  solver->setup(from_dense(D));
  Vec x;
  solver->solve(b, x);
  EXPECT_LT((x - x_ref).norm() / x_ref.norm(), 1e-12);
}

TEST_P(LUSolver, StructurallySingularMatrixThrows) {
  // Column 1 has no entries at all.
  Eigen::MatrixXd D(3, 3);
  D << 1, 0, 2,  //
      0, 0, 1,   //
      3, 0, 1;
  auto solver = make_linear_solver(GetParam());
  EXPECT_THROW(solver->setup(from_dense(D)), SolverError);
}

TEST(LinearSolver, CholmodRejectsIndefiniteMatrixAndRecovers) {
  auto solver = make_linear_solver("cholmod");
  const SparseMatrix indefinite = laplacian(20, -4.0);  // eigenvalues on both sides of 0
  try {
    solver->setup(indefinite);
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cholmod"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not positive definite"), std::string::npos) << msg;
  }
  // Same pattern, SPD values: the kept analysis must still give a correct factorization.
  const SparseMatrix spd = laplacian(20, 0.3);
  solver->setup(spd);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  const Vec b = random_vector(spd.rows(), 11);
  Vec x;
  solver->solve(b, x);
  EXPECT_LT(relative_residual(spd, x, b), 1e-10);
}

TEST(LinearSolver, CholmodRejectsNegativeDefiniteMatrix) {
  SparseMatrix A = laplacian(5, 0.1);
  A = -A;
  for (const char* type : {"cholmod", "cholmod_supernodal"}) {
    auto solver = make_linear_solver(type);
    EXPECT_THROW(solver->setup(A), SolverError) << type;
  }
}

TEST(LinearSolver, UnknownTypeThrowsInvalidArgumentListingTheValidTypes) {
  try {
    make_linear_solver("pardiso");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'pardiso'"), std::string::npos) << msg;
    for (const auto& t : direct_solver_types()) EXPECT_NE(msg.find(t), std::string::npos) << msg;
  }
  EXPECT_THROW(make_linear_solver(""), std::invalid_argument);
  EXPECT_THROW(make_linear_solver("CHOLMOD"), std::invalid_argument);
}

TEST(LinearSolver, TypeListIsComplete) {
  EXPECT_EQ(direct_solver_types(), kAll);
  for (const auto& t : direct_solver_types()) EXPECT_NO_THROW(make_linear_solver(t));
  std::vector<std::string> all = kAll;
  all.push_back("petsc");
  all.push_back("auto");
  EXPECT_EQ(linear_solver_types(), all);
}
