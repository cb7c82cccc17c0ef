#pragma once
/// @file petsc_solver.hpp
/// The PETSc backend of lagfsi::LinearSolver (private to the core: no PETSc type leaves petsc_solver.cpp).
#include <lagfsi/linear_solver.hpp>

#include <memory>

namespace lagfsi {

/// A PETSc Krylov solver for `settings.kind` (petsc_solver.cpp lists the defaults); PETSc starts with the
/// first one.
std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverSettings& settings);

}  // namespace lagfsi
