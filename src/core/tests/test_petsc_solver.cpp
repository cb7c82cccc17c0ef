// Unit tests of the iterative backend and "auto" (linear_solver.hpp, petsc_solver.cpp): each kind's default
// reaches the contract's tolerance, a saddle-point system matches the direct solution, a solve that cannot
// converge fails with its reason and the solver recovers, pattern reuse, per-solver options, and the case
// file's `linear_solver` value (linear_solver_input.hpp).
#include <lagfsi/error.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/linear_solver_input.hpp>

#include <gtest/gtest.h>

#include "test_systems.hpp"

#include <string>
#include <vector>

using namespace lagfsi;
using namespace lagfsi::testing;

namespace {

double relative_residual(const SparseMatrix& A, const Vec& x, const Vec& b) { return (A * x - b).norm() / b.norm(); }

LinearSolverSettings petsc(SystemKind kind, int block_size = 1) {
  LinearSolverSettings s;
  s.type = "petsc";
  s.kind = kind;
  s.block_size = block_size;
  return s;
}

}  // namespace

TEST(PetscSolver, CgWithAlgebraicMultigridReachesTheToleranceOnAPoissonSystem) {
  const SparseMatrix A = laplacian(60, 1e-3);
  auto solver = make_linear_solver(petsc(SystemKind::symmetric_positive_definite));
  solver->setup(A);
  const Vec b = random_vector(A.rows(), 1);
  Vec x;
  solver->solve(b, x);
  EXPECT_EQ(solver->report().method, "cg/hypre");
  EXPECT_GT(solver->report().iterations, 0);
  EXPECT_LT(solver->report().iterations, 30);  // multigrid: a few iterations, not ~n
  EXPECT_LE(relative_residual(A, x, b), 1e-8);
  EXPECT_NEAR(solver->report().residual, relative_residual(A, x, b), 1e-12);
}

TEST(PetscSolver, MassDominatedSystemsUseJacobiPreconditionedCg) {
  SparseMatrix A = laplacian(30, 50.0);
  auto solver = make_linear_solver(petsc(SystemKind::mass_dominated));
  solver->setup(A);
  const Vec b = random_vector(A.rows(), 2);
  Vec x;
  solver->solve(b, x);
  EXPECT_EQ(solver->report().method, "cg/jacobi");
  EXPECT_LE(relative_residual(A, x, b), 1e-8);
}

TEST(PetscSolver, SaddlePointFieldSplitMatchesTheDirectSolution) {
  const SparseMatrix A = saddle_point(24, 1.0, 1e-2);
  const Vec b = random_vector(A.rows(), 3);
  auto direct = make_linear_solver("klu");
  direct->setup(A);
  Vec x_direct;
  direct->solve(b, x_direct);
  auto solver = make_linear_solver(petsc(SystemKind::saddle_point, 3));
  solver->setup(A);
  Vec x;
  solver->solve(b, x);
  EXPECT_EQ(solver->report().method, "fgmres/fieldsplit");
  EXPECT_LE(relative_residual(A, x, b), 1e-8);
  EXPECT_LT((x - x_direct).norm(), 1e-6 * x_direct.norm());
}

TEST(PetscSolver, TheSaddlePointsNestOfBlocksSolvesAsTheWholeMatrixDoesAndFollowsNewValues) {
  // The default field split takes the velocity and pressure blocks of a nest; a case file's own fields keep the
  // whole matrix. Both reach the same solution; new values on the same pattern reach the nest's blocks and their
  // preconditioners (2 A x = b gives half the solution), and a new pattern makes a new nest.
  const SparseMatrix A = saddle_point(24, 1.0, 1e-2);
  const Vec b = random_vector(A.rows(), 3);
  auto nest = make_linear_solver(petsc(SystemKind::saddle_point, 3));
  LinearSolverSettings whole_settings = petsc(SystemKind::saddle_point, 3);
  whole_settings.options = "-pc_fieldsplit_0_fields 0,1 -pc_fieldsplit_1_fields 2";
  auto whole = make_linear_solver(whole_settings);
  Vec x_nest, x_whole;
  nest->setup(A);
  nest->solve(b, x_nest);
  whole->setup(A);
  whole->solve(b, x_whole);
  EXPECT_LE(relative_residual(A, x_nest, b), 1e-8);
  EXPECT_LT((x_nest - x_whole).norm(), 1e-7 * x_whole.norm());
  const SparseMatrix A2 = 2.0 * A;
  nest->setup(A2);
  Vec x_half;
  nest->solve(b, x_half);
  EXPECT_LE(relative_residual(A2, x_half, b), 1e-8);
  EXPECT_LT((2.0 * x_half - x_nest).norm(), 1e-7 * x_nest.norm());
  EXPECT_EQ(nest->statistics().pattern_setups, 1);
  const SparseMatrix B = saddle_point(30, 1.0, 1e-2);
  const Vec c = random_vector(B.rows(), 4);
  Vec y;
  nest->setup(B);
  nest->solve(c, y);
  EXPECT_LE(relative_residual(B, y, c), 1e-8);
  EXPECT_EQ(nest->statistics().pattern_setups, 2);
}

TEST(PetscSolver, AReleasedSolverRefusesToSolveUntilItsNextSetupWhichStartsAnew) {
  const SparseMatrix A = saddle_point(24, 1.0, 1e-2);
  const Vec b = random_vector(A.rows(), 5);
  auto solver = make_linear_solver(petsc(SystemKind::saddle_point, 3));
  solver->setup(A);
  Vec x;
  solver->solve(b, x);
  solver->release();
  Vec y;
  EXPECT_THROW(solver->solve(b, y), SolverError);
  solver->setup(A);  // the same pattern, made again: the old matrix is gone
  EXPECT_EQ(solver->statistics().pattern_setups, 2);
  solver->solve(b, y);
  EXPECT_LE(relative_residual(A, y, b), 1e-8);
  EXPECT_EQ((x - y).norm(), 0.0);  // a new matrix and preconditioner give the same bits
}

TEST(PetscSolver, GeneralSystemsUseRightPreconditionedGmres) {
  SparseMatrix A = laplacian(20, 0.5);
  A.coeffRef(0, 1) = -2.0;  // unsymmetric
  auto solver = make_linear_solver(petsc(SystemKind::general));
  solver->setup(A);
  const Vec b = random_vector(A.rows(), 4);
  Vec x;
  solver->solve(b, x);
  EXPECT_EQ(solver->report().method, "gmres/hypre");
  EXPECT_LE(relative_residual(A, x, b), 1e-8);
}

TEST(PetscSolver, ASolveThatCannotConvergeFailsWithItsReasonAndTheSolverRecovers) {
  const SparseMatrix A = laplacian(40, 1e-4);
  LinearSolverSettings s = petsc(SystemKind::symmetric_positive_definite);
  s.pc = "none";
  s.max_iterations = 3;
  auto solver = make_linear_solver(s);
  solver->setup(A);
  const Vec b = random_vector(A.rows(), 5);
  Vec x;
  try {
    solver->solve(b, x);
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("iteration limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("after 3 iterations"), std::string::npos) << msg;
    EXPECT_NE(msg.find("relative residual"), std::string::npos) << msg;
  }
  EXPECT_FALSE(solver->report().failure.empty());
  EXPECT_EQ(solver->statistics().failures, 1);
  // A solvable system afterwards: the same solver works.
  const SparseMatrix easy = laplacian(40, 1e4);  // converges in 3 unpreconditioned iterations
  solver->setup(easy);
  solver->solve(b, x);
  EXPECT_LE(relative_residual(easy, x, b), 1e-8);
  EXPECT_TRUE(solver->report().failure.empty());
}

TEST(PetscSolver, ASingularSystemWithNoSolutionIsAClearFailureNotAnAnswer) {
  // A pure-Neumann Laplacian (an enclosed fluid's pressure with no level): singular, and a right-hand side with a
  // non-zero mean has no solution. The solve must fail with its reason, not return the best it reached.
  SparseMatrix A = laplacian(20, 0.0);
  for (Index k = 0; k < A.outerSize(); ++k) {
    double off = 0.0;
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.row() != it.col()) off += it.value();
    A.coeffRef(k, k) = -off;  // rows sum to zero: constants are the null space
  }
  LinearSolverSettings s = petsc(SystemKind::symmetric_positive_definite);
  s.max_iterations = 200;
  auto solver = make_linear_solver(s);
  solver->setup(A);
  Vec x;
  try {
    solver->solve(Vec::Ones(A.rows()), x);
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("failed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("relative residual"), std::string::npos) << e.what();
  }
}

TEST(PetscSolver, RebuildsTheLayoutOnlyWhenThePatternChanges) {
  auto solver = make_linear_solver(petsc(SystemKind::symmetric_positive_definite));
  SparseMatrix A = laplacian(12, 0.1);
  A.makeCompressed();
  solver->setup(A);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  SparseMatrix A2 = A;
  for (Index k = 0; k < A2.nonZeros(); ++k) A2.valuePtr()[k] *= 2.0;
  solver->setup(A2);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  const Vec b = random_vector(A.rows(), 6);
  Vec x;
  solver->solve(b, x);
  EXPECT_LE(relative_residual(A2, x, b), 1e-8);  // the new values are the ones solved
  solver->setup(laplacian(13, 0.1));
  EXPECT_EQ(solver->symbolic_analyses(), 2);
  EXPECT_EQ(solver->statistics().setups, 3);
  EXPECT_EQ(solver->statistics().pattern_setups, 2);
}

TEST(PetscSolver, NewValuesOnTheSamePatternRebuildTheFactorization) {
  // A direct solve through PETSc (MUMPS) with a stale factorization would be wrong, not merely slower.
  LinearSolverSettings s = petsc(SystemKind::general);
  s.type = "mumps";
  auto solver = make_linear_solver(s);
  SparseMatrix A = laplacian(10, 0.5);
  A.makeCompressed();
  const Vec b = random_vector(A.rows(), 9);
  Vec x1, x2;
  solver->setup(A);
  solver->solve(b, x1);
  SparseMatrix A2 = A;
  for (Index k = 0; k < A2.nonZeros(); ++k) A2.valuePtr()[k] *= 2.0;
  solver->setup(A2);
  solver->solve(b, x2);
  EXPECT_EQ(solver->symbolic_analyses(), 1);
  EXPECT_LT(relative_residual(A2, x2, b), 1e-12);
  EXPECT_LT((2.0 * x2 - x1).norm(), 1e-12 * x1.norm());
}

TEST(PetscSolver, RawOptionsReachOnlyTheirOwnSolver) {
  LinearSolverSettings s = petsc(SystemKind::symmetric_positive_definite);
  s.options = "-ksp_type gmres -pc_type jacobi -ksp_pc_side right";
  auto mine = make_linear_solver(s);
  auto other = make_linear_solver(petsc(SystemKind::symmetric_positive_definite));
  const SparseMatrix A = laplacian(10, 1.0);
  mine->setup(A);
  other->setup(A);
  EXPECT_EQ(mine->report().method, "gmres/jacobi");
  EXPECT_EQ(other->report().method, "cg/hypre");
}

TEST(PetscSolver, AnUnknownPetscTypeIsASolverErrorNamingPetsc) {
  LinearSolverSettings s = petsc(SystemKind::general);
  s.ksp = "no_such_method";
  auto solver = make_linear_solver(s);
  try {
    solver->setup(laplacian(4, 1.0));
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("petsc"), std::string::npos) << e.what();
  }
}

TEST(PetscSolver, RejectsNonFiniteMatricesAndRightHandSides) {
  auto solver = make_linear_solver(petsc(SystemKind::symmetric_positive_definite));
  SparseMatrix A = laplacian(4, 1.0);
  Vec x;
  EXPECT_THROW(solver->solve(Vec::Ones(16), x), SolverError);  // no setup yet
  A.coeffRef(3, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver->setup(A), SolverError);
  solver->setup(laplacian(4, 1.0));
  Vec b = Vec::Ones(16);
  b[2] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(solver->solve(b, x), SolverError);
  EXPECT_THROW(solver->solve(Vec::Ones(15), x), SolverError);
  solver->solve(Vec::Zero(16), x);  // a zero right-hand side: x = 0 without iterating
  EXPECT_EQ(x, Vec::Zero(16));
}

TEST(PetscSolver, TheContractsInputChecksNameTheSolverForEveryType) {
  // LinearSolver::setup/solve check the input once for every backend: the Krylov one, MUMPS and "auto" too.
  for (const std::string type : {"petsc", "mumps", "auto"}) {
    LinearSolverSettings s = petsc(SystemKind::general);
    s.type = type;
    auto solver = make_linear_solver(s);
    auto message = [](auto&& call) -> std::string {
      try {
        call();
      } catch (const SolverError& e) {
        return e.what();
      }
      return "no error";
    };
    Vec x;
    EXPECT_EQ(message([&] { solver->solve(Vec::Ones(9), x); }), type + ": solve() called without a successful setup()");
    EXPECT_EQ(message([&] { solver->setup(SparseMatrix(4, 5)); }), type + ": matrix is not square (4 x 5)");
    SparseMatrix bad = laplacian(3, 0.1);
    bad.uncompress();  // the check reads the used part of each column only
    bad.coeffRef(4, 4) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(message([&] { solver->setup(bad); }), type + ": matrix has non-finite entries");
    EXPECT_EQ(message([&] { solver->solve(Vec::Ones(9), x); }), type + ": solve() called without a successful setup()");
    solver->setup(laplacian(3, 0.1));
    EXPECT_EQ(message([&] { solver->solve(Vec::Ones(4), x); }),
              type + ": right-hand side has size 4, matrix has 9 rows");
    Vec b = Vec::Ones(9);
    b[1] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(message([&] { solver->solve(b, x); }), type + ": right-hand side has non-finite entries");
    EXPECT_EQ(solver->statistics().failures, 6) << type;
    solver->setup(SparseMatrix(0, 0));  // an empty system: an empty solution
    x = Vec::Ones(3);
    solver->solve(Vec(0), x);
    EXPECT_EQ(x.size(), 0) << type;
  }
}

TEST(PetscSolver, AutoIsDirectBelowTheThresholdAndKrylovFromIt) {
  LinearSolverSettings s = petsc(SystemKind::symmetric_positive_definite);
  s.type = "auto";
  s.direct = "cholmod";
  s.auto_threshold = 400;
  auto solver = make_linear_solver(s);
  const Vec b_small = random_vector(19 * 19, 7), b_large = random_vector(20 * 20, 8);
  Vec x;
  solver->setup(laplacian(19, 0.1));
  solver->solve(b_small, x);
  EXPECT_EQ(solver->report().method, "cholmod");
  EXPECT_EQ(solver->report().iterations, 0);
  const SparseMatrix A = laplacian(20, 0.1);
  solver->setup(A);
  solver->solve(b_large, x);
  EXPECT_EQ(solver->report().method, "cg/hypre");
  EXPECT_GT(solver->report().iterations, 0);
  EXPECT_LE(relative_residual(A, x, b_large), 1e-8);
  EXPECT_EQ(solver->statistics().solves, 2);
  EXPECT_EQ(solver->statistics().iterative_solves, 1);
}

TEST(LinearSolverInput, TakesATypeStringOrAnObjectAndNamesThePathOfAnError) {
  const LinearSolverSettings d = petsc(SystemKind::saddle_point, 3);
  const std::vector<std::string> direct{"klu", "umfpack"};
  Params p(Json::parse(R"({"a": "klu", "b": {"type": "petsc", "rtol": 1e-6, "pc": "jacobi"},
                           "c": {"type": "auto", "typo": 1}, "d": "cholmod", "e": {"type": "petsc", "rtol": 2}})"),
           "case.json");
  EXPECT_EQ(read_linear_solver(p, "a", d, direct).type, "klu");
  const LinearSolverSettings b = read_linear_solver(p, "b", d, direct);
  EXPECT_EQ(b.type, "petsc");
  EXPECT_EQ(b.rtol, 1e-6);
  EXPECT_EQ(b.pc, "jacobi");
  EXPECT_EQ(b.block_size, 3);  // the system's own settings are kept
  EXPECT_EQ(b.kind, SystemKind::saddle_point);
  auto message = [&](const char* key) {
    try {
      read_linear_solver(p, key, d, direct);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("c").find("/c/typo"), std::string::npos) << message("c");
  EXPECT_NE(message("d").find("/d"), std::string::npos) << message("d");  // not a direct type of this system
  EXPECT_NE(message("e").find("/e/rtol"), std::string::npos) << message("e");
}
