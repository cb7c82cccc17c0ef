// The PETSc backend with its matrix and vectors spread over MPI processes (LinearSolverSettings::distributed),
// run by CTest under `mpirun -np 2`: each process fills and solves only the rows PETSc gives it, and the
// pieces of x, summed over the processes, are the direct solution of the whole system.
#include <lagfsi/linear_solver.hpp>

#include <gtest/gtest.h>
#include <mpi.h>

#include <random>
#include <vector>

using namespace lagfsi;

namespace {

SparseMatrix laplacian(int n, double shift) {
  std::vector<Triplet> t;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0);
      if (i < n - 1) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j < n - 1) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  SparseMatrix A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// [u_x u_y p] per node: a vector Laplacian with a mass term, a centred gradient and its transpose, and a small
/// pressure Laplacian (the structure of the monolithic fluid's Newton matrix).
SparseMatrix saddle_point(int n) {
  const SparseMatrix L = laplacian(n, 0.0);
  std::vector<Triplet> t;
  for (int k = 0; k < L.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(L, k); it; ++it) {
      const Index r = it.row(), c = it.col();
      for (int d = 0; d < 2; ++d) t.emplace_back(3 * r + d, 3 * c + d, it.value() + (r == c ? 1.0 : 0.0));
      t.emplace_back(3 * r + 2, 3 * c + 2, -1e-2 * it.value());
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j;
      auto add = [&](int b, int d, double w) {
        t.emplace_back(3 * a + d, 3 * b + 2, w);
        t.emplace_back(3 * b + 2, 3 * a + d, w);
      };
      if (i + 1 < n) add(a + n, 0, 0.5);
      if (i > 0) add(a - n, 0, -0.5);
      if (j + 1 < n) add(a + 1, 1, 0.5);
      if (j > 0) add(a - 1, 1, -0.5);
    }
  SparseMatrix A(3 * n * n, 3 * n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Vec random_vector(Index n) {
  std::mt19937 gen(11);  // the same on every process
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Vec v(n);
  for (Index i = 0; i < n; ++i) v[i] = dist(gen);
  return v;
}

/// Solves A x = b distributed; checks that this process solved a part only, that the parts add up to the direct
/// solution, and that every process reports the same iterations.
void expect_distributed_solve(const SparseMatrix& A, LinearSolverSettings s, const std::string& method) {
  s.distributed = true;
  auto solver = make_linear_solver(s);  // the first one starts PETSc and MPI
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run under mpirun -np 2";
  const Vec b = random_vector(A.rows());
  Vec x;
  solver->setup(A);
  solver->solve(b, x);
  EXPECT_EQ(solver->report().method, method);
  const Index mine = (x.array() != 0.0).count();
  EXPECT_GT(mine, 0);
  EXPECT_LT(mine, A.rows());  // a part of the rows only
  Vec sum(x.size());
  MPI_Allreduce(x.data(), sum.data(), static_cast<int>(x.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  auto direct = make_linear_solver("umfpack");
  direct->setup(A);
  Vec xd;
  direct->solve(b, xd);
  EXPECT_LT((sum - xd).norm(), 1e-6 * xd.norm());
  int its = solver->report().iterations, its_max = 0;
  MPI_Allreduce(&its, &its_max, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(its, its_max);
}

}  // namespace

TEST(PetscDistributed, CgWithBoomerAmgSolvesAPoissonSystemSplitOverTwoProcesses) {
  LinearSolverSettings s;
  s.type = "petsc";
  s.kind = SystemKind::symmetric_positive_definite;
  expect_distributed_solve(laplacian(40, 1e-3), s, "cg/hypre");
}

TEST(PetscDistributed, TheSchurFieldSplitSolvesASaddlePointSystemSplitOverTwoProcesses) {
  LinearSolverSettings s;
  s.type = "petsc";
  s.kind = SystemKind::saddle_point;
  s.block_size = 3;
  expect_distributed_solve(saddle_point(16), s, "fgmres/fieldsplit");
}

TEST(PetscDistributed, MumpsFactorizesASystemSplitOverTwoProcesses) {
  LinearSolverSettings s;
  s.type = "mumps";
  expect_distributed_solve(laplacian(30, 0.5), s, "mumps");
}
