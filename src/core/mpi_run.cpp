// A run over MPI processes (mpi_run.hpp): starting MPI through PETSc, the rank and size, the decisions the
// processes take together, and a solver's settings spread over them.
#include <lagfsi/mpi_run.hpp>

#include "petsc_solver.hpp"

#include <mpi.h>

#include <cstdlib>

namespace lagfsi::mpi_run {

namespace {
bool started = false;
int my_rank = 0, my_size = 1;
}  // namespace

bool launched() {
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; Hydra (MPICH) and Slurm's PMI set PMI_SIZE; PMIx launchers
  // PMIX_RANK.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

void start() {
  if (started || !launched()) return;
  start_petsc();
  MPI_Comm_rank(MPI_COMM_WORLD, &my_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &my_size);
  started = true;
}

int rank() { return my_rank; }
int size() { return my_size; }

bool any(bool flag) {
  if (my_size <= 1) return flag;
  int f = flag ? 1 : 0, r = 0;
  MPI_Allreduce(&f, &r, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return r != 0;
}

void abort_all(int code) {
  if (my_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

LinearSolverSettings distribute(LinearSolverSettings s) {
  if (my_size <= 1) return s;
  if (s.type == "auto") s.type = "petsc";
  if (s.type == "petsc" || s.type == "mumps") s.distributed = s.gather = true;
  return s;
}

}  // namespace lagfsi::mpi_run
