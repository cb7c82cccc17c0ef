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
/// Distributed: the matrix is a PETSc AIJ matrix and the vectors PETSc vectors on a communicator
/// (PETSC_COMM_SELF, or PETSC_COMM_WORLD with LinearSolverSettings::distributed); each process inserts the rows
/// of the ownership range PETSc gives it, and the solve never gathers the system.
#include "petsc_solver.hpp"

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

namespace {

/// Throws SolverError with PETSc's text for a non-zero error code.
void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("petsc: ") + what + " failed (" + (text ? text : "PETSc error") + ")");
}

}  // namespace

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

 private:
  /// The rows [lo, hi) this process owns in a system of n rows: whole blocks of block_size rows (all rows on one
  /// process), as PETSc's default split gives them.
  std::pair<PetscInt, PetscInt> ownership(PetscInt n) const;
  /// A new matrix, vectors and KSP for a new pattern of n rows: this process's rows [lo, hi) in compressed row
  /// storage (row pointers from 0, column indices, and values or nullptr for zeros).
  void create(PetscInt n, const PetscInt* rows, const PetscInt* cols, const double* vals);
  /// A system on one process: A's rows written straight into the PETSc matrix, with no compressed-row copy of it
  /// kept (the matrix's own pattern is the one the next setup compares with). A is compressed.
  void setup_whole(const SparseMatrix& A);
  /// A distributed system: this process's rows of A into the distributed matrix. A is compressed.
  void setup_own_rows(const SparseMatrix& A);
  /// The rigid-body modes of the nodes at set_coordinates as the matrix's near-null space (rows lo..hi here).
  void set_rigid_body_modes(PetscInt lo, PetscInt hi);
  void destroy() {
    if (ksp_) KSPDestroy(&ksp_);
    if (mat_) MatDestroy(&mat_);
    if (x_) VecDestroy(&x_);
    if (b_) VecDestroy(&b_);
    ksp_ = nullptr;
    mat_ = nullptr;
    x_ = b_ = nullptr;
  }

  LinearSolverSettings s_;
  MPI_Comm comm_ = PETSC_COMM_SELF;
  std::string prefix_, options_;
  KSP ksp_ = nullptr;
  Mat mat_ = nullptr;
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

void PetscSolver::create(PetscInt n, const PetscInt* rows, const PetscInt* cols, const double* vals) {
  destroy();
  // The rows this process owns (all of them on one process), whole blocks of block_size rows.
  const PetscInt bs = s_.block_size > 1 && n % s_.block_size == 0 ? s_.block_size : 1;
  const auto [lo, hi] = ownership(n);
  check(MatCreate(comm_, &mat_), "MatCreate");
  check(MatSetSizes(mat_, hi - lo, hi - lo, n, n), "MatSetSizes");
  check(MatSetType(mat_, MATAIJ), "MatSetType");
  if (bs > 1) check(MatSetBlockSize(mat_, bs), "MatSetBlockSize");
  check(MatSetOptionsPrefix(mat_, prefix_.c_str()), "MatSetOptionsPrefix");
  check(MatSeqAIJSetPreallocationCSR(mat_, rows, cols, vals), "MatSeqAIJSetPreallocationCSR");
  check(MatMPIAIJSetPreallocationCSR(mat_, rows, cols, vals), "MatMPIAIJSetPreallocationCSR");
  check(MatSetOption(mat_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  if (coordinates_.size() == n && bs == 2) set_rigid_body_modes(lo, hi);
  check(MatCreateVecs(mat_, &x_, &b_), "MatCreateVecs");
  check(KSPCreate(comm_, &ksp_), "KSPCreate");
  check(KSPSetOptionsPrefix(ksp_, prefix_.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetOperators(ksp_, mat_, mat_), "KSPSetOperators");
  check(KSPSetTolerances(ksp_, s_.rtol, 1e-300, PETSC_DEFAULT, s_.max_iterations), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions (check the solver's options)");
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
  check(MatSetNearNullSpace(mat_, modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);
  VecDestroy(&xy);
}

void PetscSolver::setup_whole(const SparseMatrix& A) {
  const auto n = static_cast<PetscInt>(A.rows());
  const int* op = A.outerIndexPtr();
  const int* ip = A.innerIndexPtr();
  const double* vp = A.valuePtr();
  const Index nnz = A.nonZeros();
  // Row pointers of A's rows (A is stored by columns).
  std::vector<PetscInt> rows(static_cast<size_t>(n) + 1, 0);
  for (Index k = 0; k < nnz; ++k) ++rows[static_cast<size_t>(ip[k]) + 1];
  for (size_t r = 1; r < rows.size(); ++r) rows[r] += rows[r - 1];
  // next[r]: where row r's next entry goes; the columns come in increasing order, so each row's stay sorted.
  std::vector<PetscInt> next;
  auto each_entry = [&](const auto& fn) {
    next.assign(rows.begin(), rows.end() - 1);
    for (Index col = 0; col < A.outerSize(); ++col)
      for (int k = op[col]; k < op[col + 1]; ++k) fn(next[static_cast<size_t>(ip[k])]++, static_cast<PetscInt>(col), k);
  };
  // The same pattern as the matrix's own (compared with PETSc's arrays, not with a copy of them).
  bool same = false;
  if (mat_) {
    PetscInt nr = 0;
    const PetscInt *ia = nullptr, *ja = nullptr;
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(mat_, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done), "MatGetRowIJ");
    same = done && nr == n && std::equal(rows.begin(), rows.end(), ia);
    if (same) each_entry([&](PetscInt at, PetscInt col, int) { same = same && ja[at] == col; });
    check(MatRestoreRowIJ(mat_, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done), "MatRestoreRowIJ");
  }
  if (!same) {
    destroy();  // the old matrix and preconditioner let go before the new ones are built
    std::vector<PetscInt> cols(static_cast<size_t>(nnz));
    each_entry([&](PetscInt at, PetscInt col, int) { cols[static_cast<size_t>(at)] = col; });
    create(n, rows.data(), cols.data(), nullptr);
  }
  PetscScalar* a = nullptr;
  check(MatSeqAIJGetArrayWrite(mat_, &a), "MatSeqAIJGetArrayWrite");
  each_entry([&](PetscInt at, PetscInt, int k) { a[at] = vp[k]; });
  check(MatSeqAIJRestoreArrayWrite(mat_, &a), "MatSeqAIJRestoreArrayWrite");
  // New values on the same operator: without this the KSP keeps the preconditioner (or a direct factorization)
  // of the old values.
  if (same) check(KSPSetOperators(ksp_, mat_, mat_), "KSPSetOperators");
}

void PetscSolver::setup_own_rows(const SparseMatrix& A) {
  const auto n = static_cast<PetscInt>(A.rows());
  const auto [lo, hi] = ownership(n);
  const PetscInt m = hi - lo;
  const int* op = A.outerIndexPtr();
  const int* ip = A.innerIndexPtr();
  const double* vp = A.valuePtr();
  // fn(local row, column, k) on A's entries in this process's rows, column by column (so each row's columns come in
  // increasing order). The other rows stay empty: they may be another process's to assemble.
  auto each_own = [&](const auto& fn) {
    for (Index col = 0; col < A.outerSize(); ++col)
      for (int k = op[col]; k < op[col + 1]; ++k)
        if (ip[k] >= lo && ip[k] < hi) fn(static_cast<PetscInt>(ip[k] - lo), static_cast<PetscInt>(col), k);
  };
  std::vector<PetscInt> rows(static_cast<size_t>(m) + 1, 0);
  each_own([&](PetscInt r, PetscInt, int) { ++rows[static_cast<size_t>(r) + 1]; });
  for (size_t r = 1; r < rows.size(); ++r) rows[r] += rows[r - 1];
  // The matrix's two blocks (MatMPIAIJGetSeqAIJ): columns [lo, hi) in the diagonal one (local column numbers), the
  // others in the off-diagonal one (compressed numbers, garray[] their columns in increasing order). A row's entries
  // in the order of their columns therefore go to the next place of that row in one block or the other.
  struct Blocks {
    Mat d = nullptr, o = nullptr;
    const PetscInt* garray = nullptr;
    const PetscInt *di = nullptr, *dj = nullptr, *oi = nullptr, *oj = nullptr;
    PetscInt dn = 0, on = 0;
    PetscBool dok = PETSC_FALSE, ook = PETSC_FALSE;
  } b;
  auto open_blocks = [&] {
    check(MatMPIAIJGetSeqAIJ(mat_, &b.d, &b.o, &b.garray), "MatMPIAIJGetSeqAIJ");
    check(MatGetRowIJ(b.d, 0, PETSC_FALSE, PETSC_FALSE, &b.dn, &b.di, &b.dj, &b.dok), "MatGetRowIJ");
    check(MatGetRowIJ(b.o, 0, PETSC_FALSE, PETSC_FALSE, &b.on, &b.oi, &b.oj, &b.ook), "MatGetRowIJ");
  };
  auto close_blocks = [&] {
    check(MatRestoreRowIJ(b.d, 0, PETSC_FALSE, PETSC_FALSE, &b.dn, &b.di, &b.dj, &b.dok), "MatRestoreRowIJ");
    check(MatRestoreRowIJ(b.o, 0, PETSC_FALSE, PETSC_FALSE, &b.on, &b.oi, &b.oj, &b.ook), "MatRestoreRowIJ");
  };
  std::vector<PetscInt> nd, no;            // each row's next place in the diagonal and the off-diagonal block
  auto each_place = [&](const auto& fn) {  // fn(in diagonal block, place, column, k)
    nd.assign(b.di, b.di + m);
    no.assign(b.oi, b.oi + m);
    each_own([&](PetscInt r, PetscInt col, int k) {
      const bool diag = col >= lo && col < hi;
      fn(diag, diag ? nd[static_cast<size_t>(r)]++ : no[static_cast<size_t>(r)]++, r, col, k);
    });
  };
  // The same pattern as the matrix's own (compared with its blocks, not with a copy of them).
  int same = 0;
  if (mat_) {
    open_blocks();
    same = b.dok && b.ook && b.dn == m && b.on == m;
    for (PetscInt r = 0; same && r < m; ++r)
      same = (b.di[r + 1] - b.di[r]) + (b.oi[r + 1] - b.oi[r]) ==
             rows[static_cast<size_t>(r) + 1] - rows[static_cast<size_t>(r)];
    if (same)
      each_place([&](bool diag, PetscInt at, PetscInt r, PetscInt col, int) {
        const PetscInt end = diag ? b.di[r + 1] : b.oi[r + 1];
        same = same && at < end && (diag ? b.dj[at] + lo : b.garray[b.oj[at]]) == col;
      });
    close_blocks();
  }
  // Creating the matrix is collective: every process takes the same branch.
  const double t0 = MPI_Wtime();
  MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm_);
  mpi_run::note_traffic(MPI_Wtime() - t0, mpi_run::allreduce_bytes(sizeof same));
  if (!same) {
    destroy();  // the old matrix and preconditioner let go before the new ones are built
    std::vector<PetscInt> cols(static_cast<size_t>(rows.back()));
    std::vector<PetscInt> next(rows.begin(), rows.end() - 1);
    each_own([&](PetscInt r, PetscInt col, int) { cols[static_cast<size_t>(next[static_cast<size_t>(r)]++)] = col; });
    create(n, rows.data(), cols.data(), nullptr);
  }
  // The values straight into the blocks, then an assembly (no entries to move) that marks the matrix as changed.
  open_blocks();
  PetscScalar *dv = nullptr, *ov = nullptr;
  check(MatSeqAIJGetArrayWrite(b.d, &dv), "MatSeqAIJGetArrayWrite");
  check(MatSeqAIJGetArrayWrite(b.o, &ov), "MatSeqAIJGetArrayWrite");
  each_place([&](bool diag, PetscInt at, PetscInt, PetscInt, int k) { (diag ? dv : ov)[at] = vp[k]; });
  check(MatSeqAIJRestoreArrayWrite(b.d, &dv), "MatSeqAIJRestoreArrayWrite");
  check(MatSeqAIJRestoreArrayWrite(b.o, &ov), "MatSeqAIJRestoreArrayWrite");
  close_blocks();
  check(MatAssemblyBegin(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  // New values on the same operator (as in setup_whole).
  if (same) check(KSPSetOperators(ksp_, mat_, mat_), "KSPSetOperators");
}

void PetscSolver::do_setup(const SparseMatrix& A) {
  if (A.rows() == 0) return;  // nothing to lay out; LinearSolver::solve answers an empty system itself
  if (!A.isCompressed()) {    // both paths below read the compressed arrays
    SparseMatrix C = A;
    C.makeCompressed();
    do_setup(C);
    return;
  }
  int processes = 1;
  MPI_Comm_size(comm_, &processes);
  // A distributed system on one process is a whole one (PETSc makes its matrix sequential).
  if (s_.distributed && processes > 1)
    setup_own_rows(A);
  else
    setup_whole(A);
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
  std::copy(b.data() + lo, b.data() + hi, pb);
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
  std::copy(px, px + (hi - lo), x.data() + lo);
  check(VecRestoreArrayRead(x_, &px), "VecRestoreArrayRead");
  if (s_.distributed && s_.gather) {  // each entry from one process, zeros from the others: the same bits everywhere
    const double t0 = MPI_Wtime();
    MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(n), MPIU_SCALAR, MPI_SUM, comm_);
    mpi_run::note_traffic(MPI_Wtime() - t0, mpi_run::allreduce_bytes(8.0 * static_cast<double>(n)));
  }
  // The true relative residual (one product): the report's number whatever norm the method monitored.
  ::Vec r = nullptr;
  check(VecDuplicate(b_, &r), "VecDuplicate");
  check(MatMult(mat_, x_, r), "MatMult");
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
