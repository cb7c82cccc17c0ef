// A run over MPI processes (mpi_run.hpp): starting MPI through PETSc, the rank and size, the decisions the
// processes take together, and a solver's settings spread over them.
#include <lagfsi/mpi_run.hpp>

#include "petsc_solver.hpp"

#include <mpi.h>
#include <petscsys.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>
#include <vector>

namespace lagfsi::mpi_run {

namespace {
bool started = false;
int my_rank = 0, my_size = 1;
Traffic counted;                  // the collectives' seconds and bytes (traffic())
std::atomic<double> waited{0.0};  // seconds in point-to-point waits (the MPI_Wait* wrappers at the end of this file)

/// Runs the collective `fn`, adding its wall time and the `bytes` it receives to the counts.
template <class Fn>
void timed(double bytes, Fn&& fn) {
  const double t0 = MPI_Wtime();
  fn();
  counted.seconds += MPI_Wtime() - t0;
  counted.bytes += bytes;
}
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
  timed(allreduce_bytes(sizeof f), [&] { MPI_Allreduce(&f, &r, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD); });
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
  timed(8.0 * n * (my_size - 1),
        [&] { MPI_Allgather(values, n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, MPI_COMM_WORLD); });
  for (int k = 0; k < n; ++k) {
    double s = 0;
    for (int r = 0; r < my_size; ++r)
      s += all[static_cast<size_t>(r) * static_cast<size_t>(n) + static_cast<size_t>(k)];
    values[k] = s;
  }
}

void combine_disjoint(double* values, Index n) {
  if (my_size <= 1 || n <= 0) return;
  timed(allreduce_bytes(8.0 * n), [&] { MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD); });
}

Index min(Index value) {
  if (my_size <= 1) return value;
  int v = value, r = 0;
  timed(allreduce_bytes(sizeof v), [&] { MPI_Allreduce(&v, &r, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD); });
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
  timed(4.0 * (my_size - 1), [&] { MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD); });
  long long total = 0;
  for (int r = 0; r < my_size; ++r) {
    offsets[static_cast<size_t>(r)] = static_cast<int>(total);
    total += counts[static_cast<size_t>(r)];
  }
  std::vector<Index> all(static_cast<size_t>(total));
  timed(4.0 * static_cast<double>(total - count), [&] {
    MPI_Allgatherv(mine.data(), count, MPI_INT, all.data(), counts.data(), offsets.data(), MPI_INT, MPI_COMM_WORLD);
  });
  return all;
}

void or_flags(std::uint8_t* flags, Index n) {
  if (my_size <= 1 || n <= 0) return;
  timed(allreduce_bytes(static_cast<double>(n)),
        [&] { MPI_Allreduce(MPI_IN_PLACE, flags, n, MPI_UINT8_T, MPI_MAX, MPI_COMM_WORLD); });
}

std::vector<double> gather_to_writer(const std::vector<double>& mine) {
  if (my_size <= 1) return mine;
  const int n = static_cast<int>(mine.size());
  std::vector<double> all(my_rank == 0 ? mine.size() * static_cast<size_t>(my_size) : 0);
  timed(my_rank == 0 ? 8.0 * n * (my_size - 1) : 0.0,
        [&] { MPI_Gather(mine.data(), n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD); });
  return all;
}

Traffic traffic() {
  Traffic t = counted;
  t.petsc_bytes = petsc_isend_len + petsc_send_len;
  t.halo_seconds = waited.load(std::memory_order_relaxed);
  return t;
}

void note_traffic(double seconds, double bytes) {
  counted.seconds += seconds;
  counted.bytes += bytes;
}

double allreduce_bytes(double bytes) { return my_size > 1 ? 2.0 * (my_size - 1) / my_size * bytes : 0.0; }

double peak_memory_mb() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

std::string first_failure(const std::string& message) {
  if (my_size <= 1) return message;
  const int mine = message.empty() ? my_size : my_rank;
  int first = my_size;
  timed(allreduce_bytes(sizeof mine), [&] { MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD); });
  if (first == my_size) return {};
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  std::string text = my_rank == first ? message : std::string(static_cast<size_t>(length), ' ');
  MPI_Bcast(text.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return "process " + std::to_string(first) + ": " + text;
}

}  // namespace lagfsi::mpi_run

// The point-to-point waits, timed through the MPI standard's profiling interface (PMPI): these definitions take the
// place of the library's for every caller in the process (PETSc's and hypre's halo exchanges), each calling the
// library's own PMPI_ entry. PETSc's headers define MPI_Wait* as macros that count the calls for its logging.
#undef MPI_Wait
#undef MPI_Waitall
#undef MPI_Waitany
namespace {
template <class Fn>
int waiting(Fn&& fn) {
  const double t0 = PMPI_Wtime();
  const int r = fn();
  lagfsi::mpi_run::waited.fetch_add(PMPI_Wtime() - t0, std::memory_order_relaxed);
  return r;
}
}  // namespace

extern "C" {
int MPI_Wait(MPI_Request* request, MPI_Status* status) {
  return waiting([&] { return PMPI_Wait(request, status); });
}
int MPI_Waitall(int count, MPI_Request requests[], MPI_Status statuses[]) {
  return waiting([&] { return PMPI_Waitall(count, requests, statuses); });
}
int MPI_Waitany(int count, MPI_Request requests[], int* index, MPI_Status* status) {
  return waiting([&] { return PMPI_Waitany(count, requests, index, status); });
}
}
