#pragma once
/// @file mpi_run.hpp
/// A run over MPI processes (`mpirun -n P lagfsi run CASE.json`): replicated data, divided remeshing and assembly,
/// distributed solves.
///
/// Every process builds the same case and holds every particle, node and element; each step's particle management is
/// the same computation on each (the same input, the same operations, the same results bit for bit). The fluid's linear
/// systems are PETSc matrices over all the processes, each process filling and solving the rows PETSc gives it
/// (LinearSolverSettings::distributed), and the solution is summed over the processes (each entry comes from one
/// process, the others add zeros: every process receives the same bits), so that the processes stay identical. Process
/// 0 alone writes the output folder and prints (the others run quiet), but for the models that write a piece each
/// (PhysicsModel::writes_pieces: the fluid's parallel VTK). The fluid's schemes also divide their element assembly:
/// each process computes the elements with a particle in its rows, and the per-particle sums (the residual, the
/// fractional step's forces) are combined over the processes (pspg_scheme.cpp, fractional_step.cpp). The remeshing's
/// triangulation and domain detection are divided too: each process meshes the particles of its part of space with a
/// ghost layer, and the shares are gathered (meshing::remesh_part; remesh_pipeline.cpp); so are the particle
/// management's searches, whose candidates every process then takes in particle order (divided_management.cpp). The
/// particles themselves are not divided: every process holds them all and applies the same decisions to them.
///
/// MPI starts (through PETSc, which owns it) only when an MPI launcher started the program (its environment
/// variables say so); a program run without one never starts MPI.
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/types.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi::mpi_run {

/// True when an MPI launcher (Open MPI's mpirun, or a PMI-based one) started this process.
bool launched();
/// Starts MPI (and PETSc) if launched(); call first thing in main. Idempotent.
void start();
/// This process's rank and the number of processes (0 and 1 without MPI).
int rank();
int size();
/// True on the process that writes the output (rank 0, or the only process).
inline bool writer() { return rank() == 0; }
/// True on every process when `flag` is true on at least one (a decision all of them must take together: to stop,
/// to give up).
bool any(bool flag);
/// The blocks [first, last) of `blocks` that this process owns in a system spread over the processes: PETSc's
/// default split (PetscSplitOwnership: blocks / size each, one more for the first blocks % size processes), the
/// rows a distributed PETSc matrix of that block size gives it (petsc_solver.cpp). All of them with one process.
std::pair<Index, Index> owned_blocks(Index blocks);
/// The element-wise sum of `values` (n of them) over the processes, in place, added in rank order on every
/// process (the same bits everywhere, whatever the MPI library's reduction order).
void sum_in_rank_order(double* values, int n);
/// Values each of which only one process holds (the others hold zeros) made whole on every process, in place
/// (x + 0 is exact: the same bits everywhere).
void combine_disjoint(double* values, Index n);
/// The smallest `value` over the processes.
Index min(Index value);
/// Stops every process at once with `code` (after a failure only one process saw: process 0's output); returns
/// with one process.
void abort_all(int code);
/// A solver's settings for a run over several processes: "petsc" and "mumps" spread over them with the solution
/// gathered, "auto" becoming "petsc" (a direct type stays on each process, which then solves the whole system);
/// unchanged with one process.
LinearSolverSettings distribute(LinearSolverSettings s);
/// Every process's `mine` one after the other in rank order, on every process (`mine` itself with one process).
std::vector<Index> gather_all(const std::vector<Index>& mine);
/// Every process's `mine` (the same length on each) one after the other in rank order, on process 0; empty on the
/// others (`mine` itself with one process). Every process must call it.
std::vector<double> gather_to_writer(const std::vector<double>& mine);
/// What this process has spent on communication since MPI started.
///  - seconds, bytes: the wall time of the collectives of this file and of those a caller reports (note_traffic),
///    waiting for the slower processes included, and the bytes the process received in them (an all-reduce of n
///    bytes over P processes counted as a ring's 2 (P - 1) / P n: a reduce-scatter, then an all-gather);
///  - halo_seconds: the wall time in point-to-point waits (MPI_Wait, MPI_Waitall, MPI_Waitany, timed through MPI's
///    profiling interface): the halo exchanges of PETSc's distributed products and of hypre's multigrid, waiting for
///    the other processes included (within the solver's phases; posting a message does not wait and is not counted);
///  - petsc_bytes: the bytes PETSc's point-to-point messages sent (the distributed matrices' and vectors' halo
///    exchanges, counted by PETSc's logging). hypre's messages inside its multigrid are not counted.
struct Traffic {
  double seconds = 0, bytes = 0, halo_seconds = 0, petsc_bytes = 0;
};
Traffic traffic();
/// Adds a collective made outside this file to traffic(): its wall seconds and the bytes this process received.
void note_traffic(double seconds, double bytes);
/// The bytes an all-reduce of `bytes` receives on each process, as traffic() counts them.
double allreduce_bytes(double bytes);
/// This process's peak resident memory in MiB (0 where the system does not say).
double peak_memory_mb();
/// Flags set (non-zero) on any process, set on every process, in place.
void or_flags(std::uint8_t* flags, Index n);
/// A failure some processes saw: the message of the lowest process whose `message` is not empty, on every process,
/// prefixed by that process's rank when there are several; empty when none failed. Every process must call it.
std::string first_failure(const std::string& message);

}  // namespace lagfsi::mpi_run
