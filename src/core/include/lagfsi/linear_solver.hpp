#pragma once
/// @file linear_solver.hpp
/// Sparse linear solvers, direct and iterative, behind one contract.
///
/// Contract:
///  - setup(A) prepares A x = b for solves: the pattern stage (a direct solver's fill-reducing ordering and
///    elimination tree, an iterative solver's matrix layout and preconditioner structure) is redone only when
///    the sparsity pattern differs from that of the previous call (same size, same outer/inner index arrays);
///    the numeric stage (a factorization, or a preconditioner such as algebraic multigrid) every call.
///  - solve(b, x) solves A x = b with the A of the last setup: exactly with a direct solver, to the relative
///    residual tolerance ||b - A x|| <= rtol ||b|| with an iterative one. A Krylov solve that does not reach
///    its tolerance throws lagfsi::SolverError naming the reason, the iterations and the residual reached, so
///    that the caller's step fails and is retried: never a silently inaccurate solution.
///  - report() describes the last setup and solve (method, iterations, residual, seconds, failure);
///    statistics() sums them over the solver's life (what summary.json prints).
/// Errors (singular or non-finite matrix, a solve before a setup, a right-hand side of the wrong size) throw
/// lagfsi::SolverError. setup() and solve() check their input themselves, for every backend: a matrix that is not
/// square or has a non-finite value, a solve without a successful last setup, a right-hand side of another size
/// than A or with a non-finite value; the backends see only input that passed.
///
/// Types (the string used in case files):
///  - "cholmod"     CHOLMOD simplicial Cholesky (A symmetric positive definite; lower triangle used)
///  - "cholmod_supernodal"  CHOLMOD supernodal Cholesky (faster than simplicial only with an optimized BLAS)
///  - "umfpack"     UMFPACK unsymmetric multifrontal LU
///  - "klu"         KLU (circuit-style LU; good for small, very sparse systems)
///  - "eigen_lu"    Eigen::SparseLU with COLAMD ordering
///  - "eigen_ldlt"  Eigen::SimplicialLDLT with AMD ordering (symmetric, lower triangle used)
///  - "mumps"       MUMPS multifrontal LU through PETSc (the robust direct fallback; distributed-ready)
///  - "petsc"       a PETSc Krylov solver with a preconditioner chosen for the kind of system (petsc_solver.cpp;
///                  Balay et al., PETSc/TAO Users Manual, ANL-21/39)
///  - "auto"        the direct type below `auto_threshold` unknowns, "petsc" at or above it (decided at each
///                  setup: a remesh that grows the system past the threshold switches the method)
#include <lagfsi/types.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

/// What a system is, for the iterative solver's default method (the direct solvers ignore it).
enum class SystemKind {
  symmetric_positive_definite,  ///< Poisson: CG + algebraic multigrid (BoomerAMG)
  elasticity,                   ///< a solid's tangent: CG + smoothed aggregation (GAMG) with the rigid-body modes
  mass_dominated,               ///< a mass matrix plus a small stiffness (a viscous predictor): CG + Jacobi
  saddle_point,                 ///< interleaved [u_x u_y p] per node (block size 3): FGMRES + Schur field split
  general                       ///< unsymmetric: GMRES + BoomerAMG
};

/// How a system is solved: the type string and, for "petsc" and "auto", the Krylov method's settings.
struct LinearSolverSettings {
  std::string type = "klu";  ///< one of linear_solver_types()
  SystemKind kind = SystemKind::general;
  int block_size = 1;            ///< unknowns per node (interleaved)
  std::string direct = "klu";    ///< "auto": the direct type below the threshold
  Index auto_threshold = 40000;  ///< "auto": unknowns from which the iterative solver is used
  double rtol = 1e-8;            ///< relative residual tolerance of a Krylov solve
  int max_iterations = 1000;     ///< Krylov iterations before a solve fails
  std::string ksp;               ///< PETSc KSPType ("" = the kind's default)
  std::string pc;                ///< PETSc PCType ("" = the kind's default)
  std::string options;           ///< raw PETSc options for this solver alone, e.g. "-ksp_type bcgs -pc_type ilu"
  /// PETSc types only: the matrix and vectors span every MPI process (PETSC_COMM_WORLD), each process filling
  /// and solving the rows PETSc gives it (whole blocks of block_size); setup() reads only those rows of A and
  /// solve() reads those entries of b and writes those of x (the others are zero). Off: one process
  /// (PETSC_COMM_SELF) with every row.
  bool distributed = false;
  /// Distributed: every process receives the whole x (each entry from the process that owns its row; an MPI
  /// run's replicated data, mpi_run.hpp). Off: each process's x holds its own rows, zeros elsewhere.
  bool gather = false;
};

/// The last setup and solve.
struct SolveReport {
  std::string method;  ///< the direct type, or "ksp/pc" of the Krylov solver
  Index unknowns = 0;
  int iterations = 0;          ///< Krylov iterations of the last solve (0 for a direct solve)
  double residual = 0.0;       ///< relative residual ||b - A x|| / ||b|| of the last Krylov solve (computed)
  double setup_seconds = 0.0;  ///< the last setup
  double solve_seconds = 0.0;  ///< the last solve
  std::string failure;         ///< why the last setup or solve failed ("" if it did not)
};

/// Sums over a solver's life.
struct SolverStatistics {
  long setups = 0, pattern_setups = 0, solves = 0;
  long iterations = 0, max_iterations = 0;  ///< Krylov iterations: all solves, and the largest of one solve
  long iterative_solves = 0;
  long failures = 0;  ///< setups and solves that threw (a step retry follows)
  double setup_seconds = 0.0, solve_seconds = 0.0;
  /// Adds another solver's sums (a solver replaced during a run).
  void add(const SolverStatistics& o);
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// The case-file type string.
  virtual std::string type() const = 0;
  /// True if the solver only reads the lower triangle and needs A symmetric.
  virtual bool symmetric_only() const = 0;
  /// Prepares the solves with A: pattern stage when the pattern changed, numeric stage always. A that is not square
  /// or has a non-finite value is refused before the backend sees it (the backend keeps its previous state).
  void setup(const SparseMatrix& A);
  /// Solves A x = b with the A of the last setup (b and x may alias); refused unless that setup succeeded and b
  /// is finite with A.rows() entries. An empty system (0 x 0) gives an empty x.
  void solve(const Vec& b, Vec& x);
  /// Lets the solver's copy of the matrix and its preconditioner or factorization go, when a system of a new pattern
  /// comes next (so that the old and the new are never held at once); solves are refused until the next setup.
  void release();
  /// The nodes' coordinates [x0 y0 x1 y1 ...] of a 2D elasticity system whose unknowns are interleaved per node:
  /// an algebraic multigrid then keeps the rigid-body modes (two translations, one rotation) in its coarse
  /// spaces (the near-null space). Direct solvers ignore it.
  virtual void set_coordinates(const Vec& xy) { (void)xy; }
  /// How many pattern stages were done so far (to test and report pattern reuse).
  int symbolic_analyses() const { return symbolic_count_; }
  const SolveReport& report() const { return report_; }
  const SolverStatistics& statistics() const { return stats_; }

 protected:
  /// The backend's setup of A: square with finite values (possibly 0 x 0); throws SolverError on failure.
  virtual void do_setup(const SparseMatrix& A) = 0;
  /// The backend's solve, only after a successful do_setup of a non-empty A: b finite with A.rows() entries,
  /// b and x distinct.
  virtual void do_solve(const Vec& b, Vec& x) = 0;
  /// The backend's release(): what it holds of the last setup let go (nothing by default).
  virtual void do_release() {}
  /// Throws SolverError "<type>: <reason>".
  [[noreturn]] void fail(const std::string& reason) const;
  int symbolic_count_ = 0;
  SolveReport report_;

 private:
  SolverStatistics stats_;
  bool ready_ = false;  ///< the last setup succeeded: solves are allowed
  Index rows_ = 0;      ///< the size of the A of the last setup
};

/// Builds a direct solver from its type string; throws std::invalid_argument listing the valid types.
std::unique_ptr<LinearSolver> make_linear_solver(const std::string& type);
/// Builds any solver, iterative and "auto" included; throws std::invalid_argument for an unknown type.
std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& settings);
/// The valid type strings, for error messages and documentation (direct ones, then "petsc" and "auto").
const std::vector<std::string>& linear_solver_types();
/// The direct types alone.
const std::vector<std::string>& direct_solver_types();

}  // namespace lagfsi
