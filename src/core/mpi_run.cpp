// A run over MPI processes (mpi_run.hpp): starting MPI through PETSc, the rank and size, the decisions the
// processes take together, and a solver's settings spread over them.
#include <lagfsi/mpi_run.hpp>

#include "petsc_solver.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

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

std::pair<Index, Index> owned_blocks(Index blocks) {
  if (my_size <= 1) return {0, blocks};
  const Index base = blocks / my_size, extra = blocks % my_size, r = my_rank;
  const Index first = r * base + std::min(r, extra);
  return {first, first + base + (r < extra ? 1 : 0)};
}

void sum_in_rank_order(double* values, int n) {
  if (my_size <= 1 || n <= 0) return;
  std::vector<double> all(static_cast<size_t>(n) * static_cast<size_t>(my_size));
  MPI_Allgather(values, n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, MPI_COMM_WORLD);
  for (int k = 0; k < n; ++k) {
    double s = 0;
    for (int r = 0; r < my_size; ++r)
      s += all[static_cast<size_t>(r) * static_cast<size_t>(n) + static_cast<size_t>(k)];
    values[k] = s;
  }
}

void combine_disjoint(double* values, Index n) {
  if (my_size <= 1 || n <= 0) return;
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

Index min(Index value) {
  if (my_size <= 1) return value;
  int v = value, r = 0;
  MPI_Allreduce(&v, &r, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return r;
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

std::vector<Index> gather_all(const std::vector<Index>& mine) {
  if (my_size <= 1) return mine;
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<size_t>(my_size)), offsets(static_cast<size_t>(my_size), 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  long long total = 0;
  for (int r = 0; r < my_size; ++r) {
    offsets[static_cast<size_t>(r)] = static_cast<int>(total);
    total += counts[static_cast<size_t>(r)];
  }
  std::vector<Index> all(static_cast<size_t>(total));
  MPI_Allgatherv(mine.data(), count, MPI_INT, all.data(), counts.data(), offsets.data(), MPI_INT, MPI_COMM_WORLD);
  return all;
}

void or_flags(std::uint8_t* flags, Index n) {
  if (my_size <= 1 || n <= 0) return;
  MPI_Allreduce(MPI_IN_PLACE, flags, n, MPI_UINT8_T, MPI_MAX, MPI_COMM_WORLD);
}

std::string first_failure(const std::string& message) {
  if (my_size <= 1) return message;
  const int mine = message.empty() ? my_size : my_rank;
  int first = my_size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == my_size) return {};
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  std::string text = my_rank == first ? message : std::string(static_cast<size_t>(length), ' ');
  MPI_Bcast(text.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return "process " + std::to_string(first) + ": " + text;
}

}  // namespace lagfsi::mpi_run
