#pragma once
/// @file linear_solver.hpp
/// Sparse direct solvers behind one interface.
///
/// Contract: factorize(A) performs the numeric factorization of A; the symbolic analysis (fill-reducing
/// ordering, elimination tree) is done again only when the sparsity pattern of A differs from that of
/// the matrix given to the previous call (same size, same outer/inner index arrays). solve() then
/// solves A x = b with the last factorization. Errors (singular or non-finite matrix, solve before
/// factorize) throw lagfsi::SolverError.
///
/// Types (the string used in case files):
///  - "cholmod"     CHOLMOD simplicial Cholesky (A symmetric positive definite; lower triangle used)
///  - "cholmod_supernodal"  CHOLMOD supernodal Cholesky (faster than simplicial only with an optimized BLAS)
///  - "umfpack"     UMFPACK unsymmetric multifrontal LU
///  - "klu"         KLU (circuit-style LU; good for small, very sparse systems)
///  - "eigen_lu"    Eigen::SparseLU with COLAMD ordering
///  - "eigen_ldlt"  Eigen::SimplicialLDLT with AMD ordering (symmetric, lower triangle used)
#include <lagfsi/types.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// The case-file type string.
  virtual std::string type() const = 0;
  /// True if the solver only reads the lower triangle and needs A symmetric.
  virtual bool symmetric_only() const = 0;
  /// Numeric factorization of A (symbolic analysis redone only when the pattern changed).
  virtual void factorize(const SparseMatrix& A) = 0;
  /// Solves A x = b with the last factorization.
  virtual void solve(const Vec& b, Vec& x) = 0;
  /// How many symbolic analyses were done so far (to test and report pattern reuse).
  int symbolic_analyses() const { return symbolic_count_; }

 protected:
  int symbolic_count_ = 0;
};

/// Builds a solver from its type string; throws std::invalid_argument listing the valid types.
std::unique_ptr<LinearSolver> make_linear_solver(const std::string& type);
/// The valid type strings, for error messages and documentation.
const std::vector<std::string>& linear_solver_types();

}  // namespace lagfsi
