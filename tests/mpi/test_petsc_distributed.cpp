// The PETSc backend with its matrix and vectors spread over MPI processes (LinearSolverSettings::distributed),
// run by CTest under `mpirun -np 2`: each process fills and solves only the rows PETSc gives it, and the
// pieces of x, summed over the processes, are the direct solution of the whole system.
#include <lagfsi/linear_solver.hpp>

#include <gtest/gtest.h>
#include <mpi.h>

#include "test_systems.hpp"

using namespace lagfsi;
using namespace lagfsi::testing;

namespace {

/// Solves A x = b distributed; checks that this process solved a part only, that the parts add up to the direct
/// solution, and that every process reports the same iterations.
void expect_distributed_solve(const SparseMatrix& A, LinearSolverSettings s, const std::string& method) {
  s.distributed = true;
  auto solver = make_linear_solver(s);  // the first one starts PETSc and MPI
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run under mpirun -np 2";
  const Vec b = random_vector(A.rows(), 11);
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
  expect_distributed_solve(saddle_point(16, 1.0, 1e-2), s, "fgmres/fieldsplit");
}

TEST(PetscDistributed, MumpsFactorizesASystemSplitOverTwoProcesses) {
  LinearSolverSettings s;
  s.type = "mumps";
  expect_distributed_solve(laplacian(30, 0.5), s, "mumps");
}
