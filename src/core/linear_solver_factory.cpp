/// @file linear_solver_factory.cpp
/// make_linear_solver(settings): the direct solvers, the PETSc backend and "auto", which holds one of each and
/// picks, at every setup, the direct solver below settings.auto_threshold unknowns and the Krylov one at or
/// above it. The threshold is where the bench measures the two to cost the same per unknown
/// (tests/bench/bench_scaling.py; docs/solvers.md).
#include "petsc_solver.hpp"

#include <lagfsi/linear_solver.hpp>

#include <stdexcept>

namespace lagfsi {

namespace {

class AutoSolver final : public LinearSolver {
 public:
  explicit AutoSolver(const LinearSolverSettings& s) : s_(s), direct_(make_linear_solver(s.direct)) {}
  std::string type() const override { return "auto"; }
  bool symmetric_only() const override { return direct_->symmetric_only(); }

 protected:
  void do_setup(const SparseMatrix& A) override {
    if (A.rows() >= s_.auto_threshold) {
      if (!iterative_) iterative_ = make_petsc_solver(s_);
      active_ = iterative_.get();
    } else {
      active_ = direct_.get();
    }
    report_.method = active_->type();  // what failed, if the set-up fails
    const int before = active_->symbolic_analyses();
    active_->setup(A);  // after a failure LinearSolver::solve refuses to call do_solve
    symbolic_count_ += active_->symbolic_analyses() - before;
    report_.method = active_->report().method;
  }
  void do_solve(const Vec& b, Vec& x) override {
    try {
      active_->solve(b, x);
    } catch (...) {
      report_.iterations = active_->report().iterations;
      report_.residual = active_->report().residual;
      throw;
    }
    report_.iterations = active_->report().iterations;
    report_.residual = active_->report().residual;
  }
  void do_release() override {
    direct_->release();
    if (iterative_) iterative_->release();
  }

 private:
  LinearSolverSettings s_;
  std::unique_ptr<LinearSolver> direct_, iterative_;
  LinearSolver* active_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& settings) {
  if (settings.type == "petsc" || settings.type == "mumps") return make_petsc_solver(settings);
  if (settings.type == "auto") return std::make_unique<AutoSolver>(settings);
  return make_linear_solver(settings.type);
}

}  // namespace lagfsi
