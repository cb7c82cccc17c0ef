// The EFG body's load steps: predictor and corrector iterations of the path-following control (thesis
// Algorithms 1 and 6), commit of the material history at convergence. See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/stopwatch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lagfsi::efg {

namespace {
std::string number_text(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}
}  // namespace

void EfgModel::initialize() {
  x0_ = Vec::Zero(nsys_);
  x_ = x0_;
  lambda0_ = lambda_ = 0;
  hist0_.assign(gps_.size(), History{});
  hist1_ = hist0_;
  fint0_ = Vec::Zero(nsys_);
}

void EfgModel::predict(double t_new, double dt) {
  (void)t_new;
  x_ = x0_;
  lambda_ = lambda0_;
  iter_ = 0;
  step_scale_ = dt / ctx_.analysis.dt;
  dx_step_ = Vec::Zero(nsys_);
}

IterationReport EfgModel::solve_iteration() {
  IterationReport rep;
  auto t0 = SteadyClock::now();
  assemble(x_, fint_, true);
  Vec Q = lambda_ * P_ - fint_;
  for (Index d = 0; d < nsys_; ++d)
    if (is_fixed_[d]) Q[d] = 0.0;
  rep.residual = Q.norm();
  rep.residual_ref = std::max({(lambda_ * P_).norm(), fint_.norm(), 1e-300});
  times_.assembly += seconds_since(t0);
  if (!std::isfinite(rep.residual)) fail_solve("non-finite residual at load factor " + number_text(lambda_), true);
  if (iter_ > 0 && rep.residual <= ctx_.analysis.newton.residual_tolerance * rep.residual_ref) {
    check_runaway();
    rep.converged = true;
    return rep;
  }
  if (iter_ + 1 >= ctx_.analysis.newton.max_iterations) {
    // The last iteration the driver allows, not converged: its correction would never be checked. Under load
    // control a load step that finds no equilibrium is the mark of a limit point passed; under the others, of an
    // increment too long for the path (or a body its supports do not hold).
    char m[480];
    const double relative = rep.residual / rep.residual_ref;
    if (relative < 1e-13) {
      // Equilibrium to round-off, refused by a tolerance below what doubles resolve: the tolerance is the input
      // at fault, not the step.
      std::snprintf(m, sizeof m,
                    "/analysis/newton/residual_tolerance: %.3g is below round-off: the step reached equilibrium to "
                    "a relative residual of %.3g and can go no further; give a tolerance of at least 1e-12",
                    ctx_.analysis.newton.residual_tolerance, relative);
      throw SolverError(m);
    }
    if (control_.type() == ControlType::load)
      std::snprintf(m, sizeof m,
                    "load control found no equilibrium at load factor %.6g in %d iterations (relative residual "
                    "%.3g): the load is past the body's limit point (or the step too long); follow the path past the "
                    "limit point with displacement, generalized_displacement or arc_length control",
                    lambda_, iter_ + 1, relative);
    else
      std::snprintf(m, sizeof m,
                    "no equilibrium found at load factor %.6g in %d iterations (relative residual %.3g): give a "
                    "smaller increment, or allow more analysis.newton.max_iterations",
                    lambda_, iter_ + 1, relative);
    fail_solve(m);
  }
  t0 = SteadyClock::now();
  factorize();
  times_.factorization += seconds_since(t0);
  t0 = SteadyClock::now();
  const Vec dUP = solve(P_, true);
  Vec dx;
  double dl;
  if (iter_ == 0) {  // predictor (the step starts from equilibrium: Q_0 = 0)
    dl = control_.predictor(to_control(dUP), step_scale_);
    dx = dl * dUP;
  } else {
    const Vec dUQ = solve(Q, false);
    dl = control_.corrector(to_control(dUP), to_control(dUQ), to_control(dx_step_));
    dx = dl * dUP + dUQ;
  }
  times_.solve += seconds_since(t0);
  if (!std::isfinite(dl) || !dx.allFinite())
    fail_solve("non-finite load-factor increment at load factor " + number_text(lambda_), true);
  x_ += dx;
  lambda_ += dl;
  dx_step_ += dx;
  rep.increment = dx.head(ndof_).norm();
  rep.increment_ref = std::max(x_.head(ndof_).norm(), 1e-300);
  ++iter_;
  return rep;
}

void EfgModel::finalize_step() {
  control_.commit(to_control(dx_step_));
  x0_ = x_;
  lambda0_ = lambda_;
  hist0_ = hist1_;
  fint0_ = fint_;
  lambda_peak_ = std::max(lambda_peak_, lambda0_);
  ++steps_;
}

void EfgModel::fail_solve(const std::string& reason, bool overflow_hint) const {
  // Numbers beyond the double range on the way (a stiffness, load or size far from the others) show up as
  // non-finite values or a failed factorization; the message names the control, where the step was asked for.
  const char* hint =
      overflow_hint ? " (a material stiffness, load, size or influence domain far from the others, or supports that "
                      "leave the body free to move?)"
                    : "";
  throw SolverError(control_.where() + ": " + reason + hint);
}

namespace {
/// Largest nodal displacement component of U = f(x) (node_eval: each node's support and MLS values).
double max_nodal_displacement(const std::vector<std::vector<std::pair<Index, double>>>& node_eval, const Vec& x) {
  double umax = 0;
  for (const auto& support : node_eval) {
    double ux = 0, uy = 0;
    for (const auto& [j, v] : support) {
      ux += v * x[2 * j];
      uy += v * x[2 * j + 1];
    }
    umax = std::max({umax, std::abs(ux), std::abs(uy)});
  }
  return umax;
}
}  // namespace

void EfgModel::check_runaway() const {
  const double u = max_nodal_displacement(node_eval_, x_);
  if (u <= body_size_) return;
  const double du = max_nodal_displacement(node_eval_, dx_step_);
  const std::string& at = control_.where();
  char m[560];
  if (du <= body_size_) {
    // The path itself has walked that far (a residual-strength plateau), one ordinary step at a time.
    std::snprintf(m, sizeof m,
                  "%s: the path reached a displacement of %.3g at load factor %.6g, more than the body's size %.6g: "
                  "beyond what a geometrically linear analysis describes; end the run before (fewer load steps)",
                  at.c_str(), u, lambda_, body_size_);
  } else if (linear_elastic()) {
    // No damage law to blame: the stiffness itself is far too small for the load (or the load far too large).
    std::snprintf(m, sizeof m,
                  "%s: the step to load factor %.6g moved the linear elastic body by %.3g, %.3g times its size %.6g: "
                  "beyond what a geometrically linear analysis describes (a Young's modulus far too small for the "
                  "loads, or loads far too large?)",
                  at.c_str(), lambda_, du, du / body_size_, body_size_);
  } else if (control_.type() == ControlType::load) {
    std::snprintf(m, sizeof m,
                  "%s: load control past the limit point: the step to load factor %.6g found equilibrium only at a "
                  "displacement of %.3g, %.3g times the body's size %.6g (the load exceeds what the body carries; "
                  "the damage laws' residual stiffness holds it); follow the path past the limit point with "
                  "displacement, generalized_displacement or arc_length control",
                  at.c_str(), lambda_, du, du / body_size_, body_size_);
  } else {
    std::snprintf(m, sizeof m,
                  "%s/increment: runaway step: the step to load factor %.6g moved the body by %.3g, %.3g times its "
                  "size %.6g (a geometrically linear analysis): the increment is far too large for this path; give "
                  "a smaller one",
                  at.c_str(), lambda_, du, du / body_size_, body_size_);
  }
  throw SolverError(m);
}

bool EfgModel::linear_elastic() const {
  if (!material_->linear()) return false;
  for (const auto& m : region_materials_)
    if (!m->linear()) return false;
  return true;
}

Vec EfgModel::nodal_displacements() const {
  Vec u = Vec::Zero(ndof_);
  for (Index n = 0; n < mesh_.num_nodes(); ++n)
    for (const auto& [j, v] : node_eval_[n]) {
      u[2 * n] += v * x0_[2 * j];
      u[2 * n + 1] += v * x0_[2 * j + 1];
    }
  return u;
}

Vec EfgModel::reactions() const { return (fint0_ - lambda0_ * Ptr_).head(ndof_); }

}  // namespace lagfsi::efg

namespace lagfsi {
std::unique_ptr<PhysicsModel> make_efg_model(Params body, const CaseContext& ctx) {
  return std::make_unique<efg::EfgModel>(body, ctx);
}
}  // namespace lagfsi
