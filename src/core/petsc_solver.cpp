/// @file petsc_solver.cpp
/// The iterative backend of lagfsi::LinearSolver: a PETSc KSP (Krylov method) with its PC (preconditioner),
/// chosen for the kind of system (linear_solver.hpp) and overridable by the case file.
///
/// Defaults per SystemKind (each one a string of PETSc options, read before the case file's own):
///  - symmetric_positive_definite: CG + BoomerAMG (hypre; Henson & Yang 2002), the residual measured
///    unpreconditioned so that the tolerance is the contract's ||b - A x|| <= rtol ||b||.
///  - elasticity: CG + smoothed-aggregation multigrid (GAMG; Adams et al. 2004) with the rigid-body modes of
///    set_coordinates as its near-null space (BoomerAMG without them needs twice the time on a T10 solid).
///  - mass_dominated: CG + Jacobi (a mass matrix plus dt times a stiffness is diagonally dominant).
///  - saddle_point: FGMRES on [A B^T; C D] with interleaved [u_x u_y p] unknowns, preconditioned by the
///    block upper-triangular Schur factorization (PCFIELDSPLIT, Brown et al. 2012): BoomerAMG on the
///    position block A, and BoomerAMG on S_p = D - C diag(A)^{-1} B^T ("selfp"), which for the PSPG system
///    is the stabilisation Laplacian (tau / rho) L_p plus its explicit counterpart dt^2/(c rho) L_p - the
///    pressure-Laplacian approximation of the Schur complement (Cahouet & Chabard 1988; Mardal & Winther 2011).
///  - general: GMRES (right preconditioned) + BoomerAMG.
/// Each solver has an options prefix of its own ("lagfsi<k>_"), so that two solvers of a run (a Poisson and a
/// predictor) never read each other's options; the case file's raw options are prefixed the same way.
///
/// The matrix (petsc_matrix.hpp) is a PETSc AIJ matrix, or for the saddle point's default field split a nest of its
/// velocity and pressure blocks, which the field split then uses without copying them; the vectors are PETSc
/// vectors on a communicator (PETSC_COMM_SELF, or PETSC_COMM_WORLD with LinearSolverSettings::distributed). Each
/// process writes the rows of the ownership range PETSc gives it, and the solve never gathers the system.
#include "petsc_solver.hpp"

#include "petsc_matrix.hpp"

#include <lagfsi/error.hpp>
#include <lagfsi/mpi_run.hpp>

#include <petscksp.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <sstream>
#include <utility>
#include <vector>

namespace lagfsi {

using petsc::check;

/// PETSc (and MPI under it) start with the first solver and stop at exit; PETSc's signal handlers are not
/// installed and its errors are not printed (they become SolverError).
void start_petsc() {
  static const bool started = [] {
    PetscBool initialized = PETSC_FALSE;
    PetscInitialized(&initialized);
    if (!initialized) {
      static char name[] = "lagfsi", no_signals[] = "-no_signal_handler";
      static char* args[] = {name, no_signals, nullptr};
      int argc = 2;
      char** argv = args;
      check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
      std::atexit([] { PetscFinalize(); });
    }
    PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
    return true;
  }();
  (void)started;
}

namespace {

/// The kind's default options ("mumps": PETSc's interface to the MUMPS multifrontal LU, Amestoy et al. 2001, a
/// direct solver for any kind).
std::string default_options(const LinearSolverSettings& s) {
  if (s.type == "mumps") return "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";
  switch (s.kind) {
    case SystemKind::symmetric_positive_definite:
      return "-ksp_type cg -ksp_norm_type unpreconditioned -pc_type hypre -pc_hypre_type boomeramg";
    case SystemKind::elasticity:
      return "-ksp_type cg -ksp_norm_type unpreconditioned -pc_type gamg";
    case SystemKind::mass_dominated:
      return "-ksp_type cg -ksp_norm_type unpreconditioned -pc_type jacobi";
    case SystemKind::saddle_point:
      return "-ksp_type fgmres -ksp_gmres_restart 100 -pc_type fieldsplit -pc_fieldsplit_type schur "
             "-pc_fieldsplit_schur_fact_type upper -pc_fieldsplit_schur_precondition selfp "
             "-pc_fieldsplit_0_fields 0,1 -pc_fieldsplit_1_fields 2 "
             "-fieldsplit_0_ksp_type preonly -fieldsplit_0_pc_type hypre "
             "-fieldsplit_1_ksp_type preonly -fieldsplit_1_pc_type hypre";
    case SystemKind::general:
      break;
  }
  return "-ksp_type gmres -ksp_pc_side right -ksp_gmres_restart 100 -pc_type hypre";
}

/// Whether a token of an options string names an option ("-ksp_type"), not a value ("-1e-3", "cg").
bool is_option_name(const std::string& token) {
  return token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]));
}

/// `options` with `prefix` after the dash of every option name ("-ksp_type cg" -> "-lagfsi3_ksp_type cg"); a
/// token such as "-1e-3" is a value, not a name.
std::string prefixed(const std::string& options, const std::string& prefix) {
  std::istringstream in(options);
  std::string token, out;
  while (in >> token) {
    if (is_option_name(token)) token = "-" + prefix + token.substr(1);
    out += (out.empty() ? "" : " ") + token;
  }
  return out;
}

/// The option names of a string (to clear them when the solver goes).
std::vector<std::string> option_names(const std::string& options) {
  std::istringstream in(options);
  std::vector<std::string> names;
  std::string token;
  while (in >> token)
    if (is_option_name(token)) names.push_back(token);
  return names;
}

const char* reason_text(KSPConvergedReason r) {
  switch (r) {
    case KSP_DIVERGED_ITS:
      return "iteration limit reached";
    case KSP_DIVERGED_DTOL:
      return "residual grew (divergence)";
    case KSP_DIVERGED_BREAKDOWN:
      return "Krylov breakdown";
    case KSP_DIVERGED_INDEFINITE_PC:
      return "indefinite preconditioner";
    case KSP_DIVERGED_INDEFINITE_MAT:
      return "indefinite matrix";
    case KSP_DIVERGED_NANORINF:
      return "non-finite residual";
    case KSP_DIVERGED_PC_FAILED:
      return "preconditioner set-up failed";
    default:
      return "did not converge";
  }
}

class PetscSolver final : public LinearSolver {
 public:
  explicit PetscSolver(const LinearSolverSettings& s) : s_(s) {
    start_petsc();
    if (s.distributed) comm_ = PETSC_COMM_WORLD;
    static std::atomic<int> count{0};
    prefix_ = "lagfsi" + std::to_string(count++) + "_";
    std::string opts = default_options(s);
    if (!s.ksp.empty()) opts += " -ksp_type " + s.ksp;
    if (!s.pc.empty()) opts += " -pc_type " + s.pc;
    opts += " " + s.options;
    options_ = prefixed(opts, prefix_);
    check(PetscOptionsInsertString(nullptr, options_.c_str()), "reading the options");
    matrix_ = std::make_unique<petsc::SystemMatrix>(comm_, s.block_size, nests_fields(), prefix_);
  }
  ~PetscSolver() override {
    destroy();
    for (const auto& name : option_names(options_)) PetscOptionsClearValue(nullptr, name.c_str());
  }
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  std::string type() const override { return s_.type == "mumps" ? "mumps" : "petsc"; }
  void set_coordinates(const Vec& xy) override { coordinates_ = xy; }
  bool symmetric_only() const override { return false; }

 protected:
  void do_setup(const SparseMatrix& A) override;
  void do_solve(const Vec& b, Vec& x) override;
  void do_release() override { destroy(); }

 private:
  /// The rows [lo, hi) this process owns in a system of n rows: whole blocks of block_size rows (all rows on one
  /// process), as PETSc's default split gives them.
  std::pair<PetscInt, PetscInt> ownership(PetscInt n) const;
  /// Whether the matrix is a nest of the saddle point's velocity and pressure blocks (petsc_matrix.hpp): a
  /// saddle-point system whose preconditioner, after the case file's options, is still the default field split.
  bool nests_fields() const;
  /// A new KSP and vectors for the matrix's new pattern of n rows, this process's rows [lo, hi).
  void make_solver(PetscInt n, PetscInt lo, PetscInt hi);
  /// The rigid-body modes of the nodes at set_coordinates as the matrix's near-null space (rows lo..hi here).
  void set_rigid_body_modes(PetscInt lo, PetscInt hi);
  void destroy_solver() {
    if (ksp_) KSPDestroy(&ksp_);
    if (x_) VecDestroy(&x_);
    if (b_) VecDestroy(&b_);
    ksp_ = nullptr;
    x_ = b_ = nullptr;
  }
  void destroy() {
    destroy_solver();
    if (matrix_) matrix_->destroy();
  }

  LinearSolverSettings s_;
  MPI_Comm comm_ = PETSC_COMM_SELF;
  std::string prefix_, options_;
  KSP ksp_ = nullptr;
  std::unique_ptr<petsc::SystemMatrix> matrix_;
  ::Vec x_ = nullptr, b_ = nullptr;
  Vec coordinates_;  // set_coordinates: the rigid-body near-null space's nodes
};

std::pair<PetscInt, PetscInt> PetscSolver::ownership(PetscInt n) const {
  const PetscInt bs = s_.block_size > 1 && n % s_.block_size == 0 ? s_.block_size : 1;
  PetscInt nblocks = n / bs, local_blocks = PETSC_DECIDE, first_block = 0;
  check(PetscSplitOwnership(comm_, &local_blocks, &nblocks), "PetscSplitOwnership");
  MPI_Exscan(&local_blocks, &first_block, 1, MPIU_INT, MPI_SUM, comm_);
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  if (rank == 0) first_block = 0;  // MPI_Exscan leaves the first process's result undefined
  return {first_block * bs, (first_block + local_blocks) * bs};
}

bool PetscSolver::nests_fields() const {
  if (s_.kind != SystemKind::saddle_point || s_.block_size < 2) return false;
  char pc[64] = "";
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, prefix_.c_str(), "-pc_type", pc, sizeof pc, &set), "reading the options");
  // Fields of the case file's own choosing are its to split.
  for (const char* own : {"fieldsplit_0_fields", "fieldsplit_1_fields", "fieldsplit_block_size", "fieldsplit_detect"})
    if (s_.options.find(own) != std::string::npos) return false;
  return set && std::string(pc) == PCFIELDSPLIT;
}

void PetscSolver::make_solver(PetscInt n, PetscInt lo, PetscInt hi) {
  destroy_solver();
  Mat mat = matrix_->mat();
  const PetscInt bs = s_.block_size > 1 && n % s_.block_size == 0 ? s_.block_size : 1;
  if (coordinates_.size() == n && bs == 2 && !matrix_->split()) set_rigid_body_modes(lo, hi);
  if (matrix_->split()) {  // plain vectors in the nest's order (the nest's own would be nest vectors)
    check(VecCreate(comm_, &x_), "VecCreate");
    check(VecSetSizes(x_, hi - lo, n), "VecSetSizes");
    check(VecSetType(x_, VECSTANDARD), "VecSetType");
    check(VecDuplicate(x_, &b_), "VecDuplicate");
  } else {
    check(MatCreateVecs(mat, &x_, &b_), "MatCreateVecs");
  }
  check(KSPCreate(comm_, &ksp_), "KSPCreate");
  check(KSPSetOptionsPrefix(ksp_, prefix_.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetOperators(ksp_, mat, mat), "KSPSetOperators");
  check(KSPSetTolerances(ksp_, s_.rtol, 1e-300, PETSC_DEFAULT, s_.max_iterations), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions (check the solver's options)");
  if (matrix_->split()) {  // the field split's two fields are the nest's (named as the default options name them)
    PC pc = nullptr;
    IS sets[2] = {nullptr, nullptr};
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    matrix_->field_sets(sets);
    check(PCFieldSplitSetIS(pc, "0", sets[0]), "PCFieldSplitSetIS");
    check(PCFieldSplitSetIS(pc, "1", sets[1]), "PCFieldSplitSetIS");
  }
  ++symbolic_count_;
}

void PetscSolver::set_rigid_body_modes(PetscInt lo, PetscInt hi) {
  ::Vec xy = nullptr;
  check(VecCreateMPI(comm_, hi - lo, PETSC_DETERMINE, &xy), "VecCreateMPI");
  check(VecSetBlockSize(xy, 2), "VecSetBlockSize");
  PetscScalar* p = nullptr;
  check(VecGetArray(xy, &p), "VecGetArray");
  std::copy(coordinates_.data() + lo, coordinates_.data() + hi, p);
  check(VecRestoreArray(xy, &p), "VecRestoreArray");
  MatNullSpace modes = nullptr;
  check(MatNullSpaceCreateRigidBody(xy, &modes), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(matrix_->mat(), modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);
  VecDestroy(&xy);
}

void PetscSolver::do_setup(const SparseMatrix& A) {
  if (A.rows() == 0) return;  // nothing to lay out; LinearSolver::solve answers an empty system itself
  if (!A.isCompressed()) {    // the matrix reads the compressed arrays
    SparseMatrix C = A;
    C.makeCompressed();
    do_setup(C);
    return;
  }
  // This process's rows (all of them on one process; a distributed system on one process is a whole one).
  const auto n = static_cast<PetscInt>(A.rows());
  const auto [lo, hi] = ownership(n);
  // A new pattern: the old solver (its preconditioner) let go before the new matrix is made, then a new one.
  if (matrix_->fill(A, lo, hi, [this] { destroy_solver(); }))
    make_solver(n, lo, hi);
  else  // new values on the same operator: without this the KSP keeps the preconditioner of the old values
    check(KSPSetOperators(ksp_, matrix_->mat(), matrix_->mat()), "KSPSetOperators");
  // The numeric stage (the preconditioner: multigrid hierarchy, Schur approximation) happens here, not at
  // the first solve.
  check(KSPSetUp(ksp_), "KSPSetUp (preconditioner set-up)");
  KSPType kt = nullptr;
  PCType pt = nullptr;
  PC pc = nullptr;
  KSPGetType(ksp_, &kt);
  KSPGetPC(ksp_, &pc);
  PCGetType(pc, &pt);
  report_.method = s_.type == "mumps" ? "mumps" : std::string(kt ? kt : "?") + "/" + (pt ? pt : "?");
  // A factorization that met a zero pivot (MUMPS, or an ILU/LU preconditioner) does not raise an error in PETSc:
  // it marks the preconditioner as failed.
  PCFailedReason why = PC_NOERROR;
  check(PCGetFailedReason(pc, &why), "PCGetFailedReason");
  if (why == PC_FACTOR_STRUCT_ZEROPIVOT || why == PC_FACTOR_NUMERIC_ZEROPIVOT) fail("matrix is singular (zero pivot)");
  if (why == PC_FACTOR_OUTMEMORY) fail("out of memory in the factorization");
  if (why != PC_NOERROR) fail("preconditioner set-up failed (PETSc reason " + std::to_string(int(why)) + ")");
}

void PetscSolver::do_solve(const Vec& b, Vec& x) {
  const Index n = b.size();  // the rows of the last setup (checked by LinearSolver::solve)
  x = Vec::Zero(n);
  PetscInt lo = 0, hi = 0;
  check(VecGetOwnershipRange(b_, &lo, &hi), "VecGetOwnershipRange");
  PetscScalar* pb = nullptr;
  check(VecGetArray(b_, &pb), "VecGetArray");
  matrix_->to_petsc(b.data() + lo, pb);
  check(VecRestoreArray(b_, &pb), "VecRestoreArray");
  PetscReal bnorm = 0;  // over every process's rows
  check(VecNorm(b_, NORM_2, &bnorm), "VecNorm");
  if (bnorm == 0.0) return;
  check(KSPSolve(ksp_, b_, x_), "KSPSolve");
  PetscInt its = 0;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  check(KSPGetIterationNumber(ksp_, &its), "KSPGetIterationNumber");
  check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  report_.iterations = s_.type == "mumps" ? 0 : static_cast<int>(its);  // a direct solve counts none
  const PetscScalar* px = nullptr;
  check(VecGetArrayRead(x_, &px), "VecGetArrayRead");
  matrix_->from_petsc(px, x.data() + lo);
  check(VecRestoreArrayRead(x_, &px), "VecRestoreArrayRead");
  if (s_.distributed && s_.gather) {  // each entry from one process, zeros from the others: the same bits everywhere
    const double t0 = MPI_Wtime();
    MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(n), MPIU_SCALAR, MPI_SUM, comm_);
    mpi_run::note_traffic(MPI_Wtime() - t0, mpi_run::allreduce_bytes(8.0 * static_cast<double>(n)));
  }
  // The true relative residual (one product): the report's number whatever norm the method monitored.
  ::Vec r = nullptr;
  check(VecDuplicate(b_, &r), "VecDuplicate");
  check(MatMult(matrix_->mat(), x_, r), "MatMult");
  check(VecAYPX(r, -1.0, b_), "VecAYPX");
  PetscReal rnorm = 0;
  check(VecNorm(r, NORM_2, &rnorm), "VecNorm");
  VecDestroy(&r);
  report_.residual = static_cast<double>(rnorm / bnorm);
  // A method that monitors another norm (a left-preconditioned one chosen in the options) may stop with a true
  // residual above the tolerance: beyond 10 rtol that is a failure too (below, the recurrence's round-off).
  const bool inaccurate = reason > 0 && report_.residual > 10.0 * s_.rtol;
  if (reason < 0 || inaccurate || !x.allFinite()) {
    std::ostringstream os;
    os << report_.method << ": Krylov solve of " << n
       << " unknowns failed: " << (inaccurate ? "converged in its own norm only" : reason_text(reason)) << " after "
       << its << " iterations, relative residual " << report_.residual << " (tolerance " << s_.rtol << ")";
    fail(os.str());
  }
}

}  // namespace

std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverSettings& settings) {
  return std::make_unique<PetscSolver>(settings);
}

}  // namespace lagfsi
