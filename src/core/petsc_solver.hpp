#pragma once
/// @file petsc_solver.hpp
/// The PETSc backend of lagfsi::LinearSolver (private to the core: no PETSc type leaves petsc_solver.cpp and
/// petsc_matrix.cpp).
#include <lagfsi/linear_solver.hpp>

#include <memory>

namespace lagfsi {

/// A PETSc Krylov solver for `settings.kind` (petsc_solver.cpp lists the defaults); PETSc starts with the
/// first one.
std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverSettings& settings);
/// Starts PETSc (and MPI under it) if it has not started: the first solver does, and so does an MPI run at its
/// start (mpi_run.hpp). It stops at exit.
void start_petsc();

}  // namespace lagfsi
