/// @file linear_solver.cpp
/// The contract's bookkeeping (timings, reports, statistics) and the sparse direct solvers behind
/// lagfsi::LinearSolver (see linear_solver.hpp for the contract).
///
/// Structure: LinearSolver::setup and LinearSolver::solve check the input of every backend (direct, PETSc,
/// "auto") before calling it. DirectSolverBase does the rest of what does not depend on the library (the
/// private copy of the matrix, the pattern comparison that decides whether the symbolic analysis is
/// redone, the finiteness check of the solution); each backend only implements analyze(), numeric()
/// and backsolve(). CHOLMOD is called through its C API (to report the failing column of a matrix that
/// is not positive definite and to use the supernodal factorization explicitly); UMFPACK, KLU and the
/// two Eigen solvers go through Eigen's wrappers.
///
/// The solver keeps its own compressed copy of the matrix: the pattern of the previous matrix is
/// needed for the reuse decision, and UMFPACK's solve reads the matrix again (iterative refinement),
/// so the matrix it was factorized with must outlive the caller's.
#include <lagfsi/error.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/stopwatch.hpp>

#include <cholmod.h>
#include <Eigen/KLUSupport>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace lagfsi {

namespace {

/// True if every stored value of A is finite (compressed or not: only the used part of each column is read).
bool all_finite(const SparseMatrix& A) {
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (!std::isfinite(it.value())) return false;
  return true;
}

}  // namespace

void SolverStatistics::add(const SolverStatistics& o) {
  setups += o.setups;
  pattern_setups += o.pattern_setups;
  solves += o.solves;
  iterations += o.iterations;
  max_iterations = std::max(max_iterations, o.max_iterations);
  iterative_solves += o.iterative_solves;
  failures += o.failures;
  setup_seconds += o.setup_seconds;
  solve_seconds += o.solve_seconds;
}

void LinearSolver::setup(const SparseMatrix& A) {
  const auto t0 = SteadyClock::now();
  const int analyses = symbolic_count_;
  report_.unknowns = A.rows();
  report_.failure.clear();
  ready_ = false;
  try {
    if (A.rows() != A.cols()) {
      std::ostringstream os;
      os << "matrix is not square (" << A.rows() << " x " << A.cols() << ")";
      fail(os.str());
    }
    if (!all_finite(A)) fail("matrix has non-finite entries");
    rows_ = A.rows();
    do_setup(A);
  } catch (const SolverError& e) {
    report_.failure = e.what();
    ++stats_.failures;
    report_.setup_seconds = seconds_since(t0);
    stats_.setup_seconds += report_.setup_seconds;
    throw;
  }
  ready_ = true;
  report_.setup_seconds = seconds_since(t0);
  ++stats_.setups;
  stats_.pattern_setups += symbolic_count_ - analyses;
  stats_.setup_seconds += report_.setup_seconds;
}

void LinearSolver::release() {
  do_release();
  ready_ = false;
}

void LinearSolver::solve(const Vec& b, Vec& x) {
  const auto t0 = SteadyClock::now();
  report_.iterations = 0;
  report_.residual = 0.0;
  report_.failure.clear();
  try {
    if (!ready_) fail("solve() called without a successful setup()");
    if (b.size() != rows_) {
      std::ostringstream os;
      os << "right-hand side has size " << b.size() << ", matrix has " << rows_ << " rows";
      fail(os.str());
    }
    if (!b.allFinite()) fail("right-hand side has non-finite entries");
    if (rows_ == 0) {  // nothing to solve (e.g. every degree of freedom is prescribed)
      x.resize(0);
    } else if (&b == &x) {  // the backends need distinct input and output
      const Vec copy = b;
      do_solve(copy, x);
    } else {
      do_solve(b, x);
    }
  } catch (const SolverError& e) {
    report_.failure = e.what();
    ++stats_.failures;
    report_.solve_seconds = seconds_since(t0);
    stats_.solve_seconds += report_.solve_seconds;
    stats_.iterations += report_.iterations;
    throw;
  }
  report_.solve_seconds = seconds_since(t0);
  ++stats_.solves;
  stats_.solve_seconds += report_.solve_seconds;
  if (report_.iterations > 0) {
    ++stats_.iterative_solves;
    stats_.iterations += report_.iterations;
    stats_.max_iterations = std::max<long>(stats_.max_iterations, report_.iterations);
  }
}

void LinearSolver::fail(const std::string& reason) const { throw SolverError(type() + ": " + reason); }

namespace {

/// True if a and b (both compressed) have the same size and the same outer/inner index arrays.
bool same_pattern(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const auto nnz = static_cast<std::ptrdiff_t>(a.nonZeros());
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr());
}

/// The library-independent part of every direct solver (the input is checked by LinearSolver::setup/solve).
class DirectSolverBase : public LinearSolver {
 protected:
  void do_setup(const SparseMatrix& A) final {
    report_.method = type();
    // Keep a compressed copy; reuse the analysis if the pattern did not change.
    bool same = false;
    if (A.isCompressed()) {
      same = analyzed_ && same_pattern(A, A_);
      if (same)
        std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), A_.valuePtr());
      else
        A_ = A;
    } else {
      SparseMatrix B = A;
      B.makeCompressed();
      same = analyzed_ && same_pattern(B, A_);
      if (same)
        std::copy(B.valuePtr(), B.valuePtr() + B.nonZeros(), A_.valuePtr());
      else
        A_ = std::move(B);
    }
    A_.makeCompressed();
    if (A_.rows() == 0) {  // nothing to factorize (e.g. every degree of freedom is prescribed)
      analyzed_ = true;
      return;
    }
    if (!same) {
      analyzed_ = false;
      analyze(A_);
      analyzed_ = true;
      ++symbolic_count_;
    }
    numeric(A_);
  }

  void do_solve(const Vec& b, Vec& x) final {
    backsolve(b, x);
    if (x.size() != b.size() || !x.allFinite()) fail("solution has non-finite entries (matrix numerically singular?)");
  }

  /// Symbolic analysis of A (compressed, square, finite, non-empty); throws SolverError on failure.
  virtual void analyze(const SparseMatrix& A) = 0;
  /// Numeric factorization of A (same pattern as the last analyze()); throws SolverError on failure.
  virtual void numeric(const SparseMatrix& A) = 0;
  /// x = A^{-1} b with the last factorization (b and x are distinct, b has the right size).
  virtual void backsolve(const Vec& b, Vec& x) = 0;

 private:
  SparseMatrix A_;
  bool analyzed_ = false;
};

// ------------------------------------------------------------------------------------------------ CHOLMOD

/// CHOLMOD Cholesky through the C API; reads the lower triangle only (stype = -1). Simplicial (up-looking,
/// LL^T) or supernodal (dense BLAS kernels on supernodes). With Debian's reference BLAS the supernodal
/// factorization is 2-2.4x slower on this code's 2D matrices (a 49 454-unknown T10 solid: 0.48 s against
/// 0.25 s; a 13 761-particle PFEM Poisson matrix: 3.6 against 1.5 us per particle), so "cholmod" is the
/// simplicial one and "cholmod_supernodal" is there for machines with an optimized BLAS.
class CholmodSolver final : public DirectSolverBase {
 public:
  explicit CholmodSolver(bool supernodal) : supernodal_(supernodal) {
    cholmod_start(&common_);
    common_.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    // LL^T, not the simplicial default LDL^T: LDL^T factorizes indefinite matrices without a word, and the
    // solid relies on a failure here to switch to LU when its tangent loses definiteness.
    common_.final_ll = 1;
    common_.print = 0;  // failures are reported through SolverError, not on stdout
  }
  ~CholmodSolver() override {
    if (L_) cholmod_free_factor(&L_, &common_);
    if (X_) cholmod_free_dense(&X_, &common_);
    if (Y_) cholmod_free_dense(&Y_, &common_);
    if (E_) cholmod_free_dense(&E_, &common_);
    cholmod_finish(&common_);
  }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  std::string type() const override { return supernodal_ ? "cholmod_supernodal" : "cholmod"; }
  bool symmetric_only() const override { return true; }

 protected:
  void analyze(const SparseMatrix& A) override {
    if (L_) cholmod_free_factor(&L_, &common_);
    cholmod_sparse view = make_view(A);
    L_ = cholmod_analyze(&view, &common_);
    if (!L_) fail("symbolic analysis failed (" + status_text() + ")");
  }

  void numeric(const SparseMatrix& A) override {
    cholmod_sparse view = make_view(A);
    const int ok = cholmod_factorize(&view, L_, &common_);
    if (common_.status == CHOLMOD_NOT_POSDEF || (ok && L_->minor < L_->n)) {
      std::ostringstream os;
      os << "matrix is not positive definite (factorization failed at column " << L_->minor << " of " << L_->n << ")";
      fail(os.str());
    }
    if (!ok || common_.status < CHOLMOD_OK) fail("numeric factorization failed (" + status_text() + ")");
  }

  void backsolve(const Vec& b, Vec& x) override {
    cholmod_dense B{};
    B.nrow = B.d = B.nzmax = static_cast<size_t>(b.size());
    B.ncol = 1;
    B.x = const_cast<double*>(b.data());  // CHOLMOD only reads B
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, L_, &B, nullptr, &X_, nullptr, &Y_, &E_, &common_))
      fail("solve failed (" + status_text() + ")");
    x = Eigen::Map<const Vec>(static_cast<const double*>(X_->x), b.size());
  }

 private:
  /// A CHOLMOD view of the lower triangle of A (no copy).
  static cholmod_sparse make_view(const SparseMatrix& A) {
    cholmod_sparse s{};
    s.nrow = static_cast<size_t>(A.rows());
    s.ncol = static_cast<size_t>(A.cols());
    s.nzmax = static_cast<size_t>(A.nonZeros());
    s.p = const_cast<int*>(A.outerIndexPtr());
    s.i = const_cast<int*>(A.innerIndexPtr());
    s.x = const_cast<double*>(A.valuePtr());
    s.stype = -1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;  // Eigen keeps inner indices sorted
    s.packed = 1;
    return s;
  }

  std::string status_text() const {
    switch (common_.status) {
      case CHOLMOD_OUT_OF_MEMORY:
        return "out of memory";
      case CHOLMOD_TOO_LARGE:
        return "problem too large";
      case CHOLMOD_INVALID:
        return "invalid input";
      case CHOLMOD_DSMALL:
        return "diagonal entry too small";
      default:
        return "CHOLMOD status " + std::to_string(common_.status);
    }
  }

  bool supernodal_ = false;
  cholmod_common common_{};
  cholmod_factor* L_ = nullptr;
  cholmod_dense* X_ = nullptr;  // solve2 workspaces, reused between solves
  cholmod_dense* Y_ = nullptr;
  cholmod_dense* E_ = nullptr;
};

// ------------------------------------------------------------------------------------------------ Eigen-wrapped

/// Failure descriptions for each Eigen-wrapped backend (after factorize() reported an issue).
std::string failure_reason(const Eigen::UmfPackLU<SparseMatrix>& s) {
  const int code = s.umfpackFactorizeReturncode();
  if (code == UMFPACK_WARNING_singular_matrix) return "matrix is singular";
  if (code == UMFPACK_ERROR_out_of_memory) return "out of memory";
  return "numeric factorization failed (UMFPACK status " + std::to_string(code) + ")";
}
std::string failure_reason(const Eigen::KLU<SparseMatrix>& s) {
  const klu_common& c = s.kluCommon();
  if (c.status == KLU_SINGULAR)
    return "matrix is singular (zero pivot in column " + std::to_string(c.singular_col) + ")";
  if (c.status == KLU_OUT_OF_MEMORY) return "out of memory";
  return "numeric factorization failed (KLU status " + std::to_string(c.status) + ")";
}
std::string failure_reason(const Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>>& s) {
  std::string msg = s.lastErrorMessage();
  std::transform(msg.begin(), msg.end(), msg.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return "matrix is singular (" + msg + ")";
}
std::string failure_reason(const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>&) {
  return "zero pivot in LDL^T (matrix singular, or indefinite in a way that needs pivoting)";
}

/// Whether analyzePattern() failed (Eigen::SparseLU has no analysis status: its COLAMD cannot fail).
template <class Backend>
bool analysis_failed(const Backend& s) {
  return s.info() != Eigen::Success;
}
bool analysis_failed(const Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>>&) { return false; }

/// A solver implemented by an Eigen sparse solver class (analyzePattern / factorize / info / solve).
template <class Backend>
class EigenWrappedSolver final : public DirectSolverBase {
 public:
  EigenWrappedSolver(std::string name, bool symmetric) : name_(std::move(name)), symmetric_(symmetric) {}
  std::string type() const override { return name_; }
  bool symmetric_only() const override { return symmetric_; }

 protected:
  void analyze(const SparseMatrix& A) override {
    backend_.analyzePattern(A);
    if (analysis_failed(backend_)) fail("symbolic analysis failed");
  }
  void numeric(const SparseMatrix& A) override {
    backend_.factorize(A);
    if (backend_.info() != Eigen::Success) fail(failure_reason(backend_));
  }
  void backsolve(const Vec& b, Vec& x) override {
    x = backend_.solve(b);
    if (backend_.info() != Eigen::Success) fail("solve failed");
  }

 private:
  std::string name_;
  bool symmetric_;
  Backend backend_;
};

}  // namespace

const std::vector<std::string>& direct_solver_types() {
  static const std::vector<std::string> types{"cholmod",  "cholmod_supernodal", "umfpack", "klu",
                                              "eigen_lu", "eigen_ldlt",         "mumps"};
  return types;
}

const std::vector<std::string>& linear_solver_types() {
  static const std::vector<std::string> types = [] {
    std::vector<std::string> t = direct_solver_types();
    t.push_back("petsc");
    t.push_back("auto");
    return t;
  }();
  return types;
}

std::unique_ptr<LinearSolver> make_linear_solver(const std::string& type) {
  if (type == "cholmod") return std::make_unique<CholmodSolver>(false);
  if (type == "cholmod_supernodal") return std::make_unique<CholmodSolver>(true);
  if (type == "umfpack") return std::make_unique<EigenWrappedSolver<Eigen::UmfPackLU<SparseMatrix>>>(type, false);
  if (type == "klu") return std::make_unique<EigenWrappedSolver<Eigen::KLU<SparseMatrix>>>(type, false);
  if (type == "eigen_lu")
    return std::make_unique<EigenWrappedSolver<Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>>>>(type, false);
  if (type == "eigen_ldlt")
    return std::make_unique<
        EigenWrappedSolver<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>>(type, true);
  if (type == "petsc" || type == "auto" || type == "mumps") {
    LinearSolverSettings s;
    s.type = type;
    return make_linear_solver(s);
  }
  std::string valid;
  for (const auto& t : direct_solver_types()) valid += (valid.empty() ? "" : ", ") + t;
  throw std::invalid_argument("unknown direct linear solver '" + type + "' (valid: " + valid + ")");
}

}  // namespace lagfsi
