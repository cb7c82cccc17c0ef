#pragma once
/// @file linear_solver_input.hpp
/// The case file's `linear_solver` value, wherever a system is solved: a type string ("klu", "petsc", "auto",
/// ...) or an object with the type and the Krylov solver's settings (its KeyTable is in the case-file
/// reference: "linear solver (object form)"); and the solver's record in summary.json.
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/params.hpp>

#include <string>
#include <vector>

namespace lagfsi {

/// The string form of `parent`'s `key` ("petsc") becomes the object form ({"type": "petsc"}): call it before
/// validating `parent` against a KeyTable that declares `key` with an object default.
void expand_linear_solver(Params& parent, const std::string& key);

/// Reads `parent`'s `key` (present: the caller's KeyTable gives its default) into a copy of `defaults` (which
/// carries the system's kind, block size and direct type). `direct_types` are the direct solvers this system
/// accepts; "petsc" and "auto" are always accepted. Errors name the JSON path.
LinearSolverSettings read_linear_solver(const Params& parent, const std::string& key, LinearSolverSettings defaults,
                                        const std::vector<std::string>& direct_types);

/// The summary.json record of a solver's life: its type and last method, setups (and pattern setups), solves,
/// Krylov iterations per solve (mean and largest), failures, seconds in setups and in solves.
Json solver_summary(const LinearSolver& solver);

/// A one-line description of the values accepted, for the KeyTables of the systems: "<direct types>, petsc or
/// auto, or an object (see linear solver (object form))".
std::string linear_solver_doc(const std::vector<std::string>& direct_types);

}  // namespace lagfsi
