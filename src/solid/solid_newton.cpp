// The Newton iterations of a solid or shell step (solid_model_impl.hpp): the residual and tangent with the
// time integrator (or the load factor in statics), follower loads, Rayleigh damping, prescribed dofs and the
// factorization (with its fallback to LU).
#include "solid_model_impl.hpp"

#include <lagfsi/system_assembly.hpp>

namespace lagfsi::solid {

Vec SolidModel::external_force(double t, const Vec& x) const {
  Vec f = Vec::Zero(body_->num_dofs());
  for (const auto& l : loads_) f += l.fn->value(t) * (l.follower.size() ? Vec(l.follower * x) : l.f);
  return load_factor(t) * f;
}

void SolidModel::add_follower_tangent(double t, double scale, SparseMatrix& H) const {
  // r = ... - f_ext(x): d r / dx = -fn(t) lambda P on the body's pattern.
  double* h = H.valuePtr();
  for (const auto& l : loads_) {
    if (!l.follower.size()) continue;
    const double c = scale * l.fn->value(t) * load_factor(t);
    const double* pv = l.follower.valuePtr();
    for (Index i = 0; i < H.nonZeros(); ++i) h[i] -= c * pv[i];
  }
}

void SolidModel::impose_prescribed(double t, Vec& x) const {
  const Vec& X = body_->reference_positions();
  for (const auto& p : prescribed_) {
    double u = 0.0;
    if (p.fn) u = p.amplitude * (p.velocity ? p.fn->integral(t) : p.fn->value(t)) * load_factor(t);
    x[p.dof] = X[p.dof] + u;
  }
}

Vec SolidModel::damping_times(const Vec& v) const {
  Vec r = Vec::Zero(v.size());
  if (damp_mass_ > 0) r += damp_mass_ * (body_->mass() * v);
  if (damp_stiff_ > 0) r += damp_stiff_ * (K0_ * v);
  return r;
}

void SolidModel::apply_dirichlet(SparseMatrix& H, Vec& r) const { dirichlet_identity(H, r, fixed_mask_); }

void SolidModel::make_solver() {
  solver_ = make_linear_solver(solver_settings_);
  // Positions alone per node (a plane solid): the rigid-body modes for an algebraic multigrid.
  if (solver_settings_.block_size == 2) solver_->set_coordinates(body_->reference_positions());
}

void SolidModel::factorize(const SparseMatrix& H) {
  try {
    solver_->setup(H);
  } catch (const SolverError& e) {
    // The direct Cholesky alone (also inside "auto"): an iterative solver's failure is not about definiteness.
    if (solver_->report().method.rfind("cholmod", 0) != 0) throw;
    // Non-finite entries are not a matter of definiteness: LU would fail the same way.
    if (!std::all_of(H.valuePtr(), H.valuePtr() + H.nonZeros(), [](double v) { return std::isfinite(v); })) throw;
    // An indefinite tangent (buckling, strong compression): switch to LU for the rest of the run. The
    // warning comes once the LU has factorized, so that a run that fails says it in one line.
    solver_settings_.type = "umfpack";
    make_solver();
    solver_->setup(H);
    fallback_note_ = std::string(e.what()) + "; switched to umfpack at t = " + std::to_string(t_new_);
    if (!ctx_.quiet) std::cerr << "lagfsi: warning: body '" << name_ << "': " << fallback_note_ << "\n";
  }
}

IterationReport SolidModel::solve_iteration() {
  // The element kernels do not know the body: name it in their failures ("element 3: inverted element").
  try {
    return newton_iteration();
  } catch (const SolverError& e) {
    const std::string what = e.what();
    if (what.rfind("body '", 0) == 0) throw;
    throw SolverError("body '" + name_ + "': " + what);
  }
}

IterationReport SolidModel::newton_iteration() {
  auto t0 = SteadyClock::now();
  IterationReport rep;
  Vec r;
  const Index nd = body_->num_dofs();
  if (is_static_) {
    strain_energy_ = body_->internal_force(x_, f_int_, &H_);
    const Vec fext = external_force(t_new_, x_);
    r = f_int_ - fext;
    add_follower_tangent(t_new_, 1.0, H_);
    // Force scale: the loads and internal forces, but at least the force of a stiffness-scale deformation of
    // 1e-6 of the body's size (a rigid prescribed motion has no force at all to compare with).
    double kmax = 0;
    for (int k = 0; k < H_.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(H_, k); it; ++it)
        if (it.row() == it.col()) kmax = std::max(kmax, std::abs(it.value()));
    rep.residual_ref = std::max({fext.norm(), f_int_.norm(), 1e-6 * kmax * length_});
  } else {
    const EvalPoint ev = integrator_->kinematics(x_);
    const TangentCoefficients c = integrator_->coefficients();
    strain_energy_ = body_->internal_force(ev.x, f_int_, &H_);
    Vec fext = external_force(ev.t, ev.x);
    if (f_iface_.size() == nd) fext += f_iface_;
    const Vec inertia = body_->mass() * ev.a;
    const Vec damping = damping_times(ev.v);
    r = inertia + damping + f_int_ - fext;
    // Augmented mass of a coupling iterate: (factor - 1) c_m M (x - x_prev), zero at convergence.
    const bool augmented = aug_factor_ > 1.0 && x_aug_prev_.size() == nd;
    if (augmented) r += (aug_factor_ - 1.0) * c.c_m * (body_->mass() * (x_ - x_aug_prev_));
    // H = c_m M + c_c C + c_k K, all on the same pattern (C = damp_mass M + damp_stiff K0).
    const double cm = c.c_m * (augmented ? aug_factor_ : 1.0) + c.c_c * damp_mass_;
    combine_tangent(H_, c.c_k, cm, body_->mass(), c.c_c * damp_stiff_, damp_stiff_ > 0 ? &K0_ : nullptr);
    add_follower_tangent(ev.t, c.c_k, H_);
    Vec rf = fext, ri = inertia, ru = f_int_;
    for (Index i = 0; i < nd; ++i)
      if (fixed_mask_[i]) rf[i] = ri[i] = ru[i] = 0.0;
    rep.residual_ref = std::max({rf.norm(), ri.norm(), ru.norm()});
  }
  apply_dirichlet(H_, r);
  rep.residual = r.norm();
  if (!std::isfinite(rep.residual)) throw SolverError("body '" + name_ + "': non-finite residual");
  times_.assembly += seconds_since(t0);
  rep.increment_ref = length_;
  // Converged already (small residual at the updated x after a small last correction): no solve.
  // The residual of a positional formulation has a round-off floor (F = x^T G is computed from absolute
  // coordinates, so its error is about eps |x| |G|); a residual that stopped decreasing after a
  // correction below the position tolerance is at that floor and is accepted as converged.
  const NewtonSettings& nw = ctx_.analysis.newton;
  const double rref = std::max(rep.residual_ref, 1e-300);
  const bool small_step = last_increment_ <= nw.position_tolerance * length_;
  const bool at_floor = small_step && rep.residual > 0.5 * last_residual_ && rep.residual <= 1e-3 * rref;
  last_residual_ = rep.residual;
  if ((rep.residual <= nw.residual_tolerance * rref && small_step) || at_floor) {
    rep.increment = last_increment_;
    rep.converged = true;
    return rep;
  }

  t0 = SteadyClock::now();
  factorize(H_);
  times_.factorization += seconds_since(t0);
  t0 = SteadyClock::now();
  Vec dx;
  solver_->solve(-r, dx);
  times_.solve += seconds_since(t0);
  x_ += dx;
  rep.increment = dx.norm();
  last_increment_ = rep.increment;

  if (!x_.allFinite()) throw SolverError("body '" + name_ + "': non-finite positions");
  return rep;
}

}  // namespace lagfsi::solid
