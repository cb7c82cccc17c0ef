// The solid or shell body as a PhysicsModel (solid_model_impl.hpp): its lifecycle (initialize, predict,
// finalize_step, output) and the coupling side (InterfaceStructure). The body is read by solid_input.cpp, a
// step's Newton iterations are in solid_newton.cpp, the probes in solid_probes.cpp.
#include "solid_model_impl.hpp"

namespace lagfsi::solid {

// ------------------------------------------------------------------------------------------ lifecycle

void SolidModel::initialize() {
  auto t0 = SteadyClock::now();
  if (damp_stiff_ > 0) {
    K0_ = body_->pattern();
    Vec f;
    body_->internal_force(body_->reference_positions(), f, &K0_);
  }
  impose_prescribed(0.0, state_.x);
  Vec f;
  strain_energy_ = body_->internal_force(state_.x, f, nullptr);
  energy0_ = kinetic_energy() + strain_energy_;
  if (!is_static_) {
    // Consistent initial acceleration: M a0 = f_ext(0) - f_int(x0) - C v0 on the free dofs.
    Vec r = external_force(0.0, state_.x) - f - damping_times(state_.v);
    SparseMatrix M = body_->mass();
    apply_dirichlet(M, r);
    auto s = make_linear_solver("cholmod");
    s->setup(M);
    s->solve(r, state_.a);
    for (const auto& p : prescribed_) state_.a[p.dof] = 0.0;
  }
  times_.assembly += seconds_since(t0);
}

void SolidModel::predict(double t_new, double dt) {
  // Retry-safe: the iterations change only the iterate x_ (state_ changes in finalize_step), so a predict
  // after a failed attempt starts the smaller step from the same committed state.
  old_state_ = state_;
  t_new_ = t_new;
  dt_ = dt;
  if (is_static_) {
    x_ = state_.x;
  } else {
    integrator_->begin_step(state_, dt);
    x_ = integrator_->predictor();
  }
  impose_prescribed(t_new, x_);
  last_increment_ = std::numeric_limits<double>::infinity();
  last_residual_ = std::numeric_limits<double>::infinity();
}

void SolidModel::finalize_step() {
  auto t0 = SteadyClock::now();
  const Vec x_old = state_.x;
  const Vec fext_old = external_force(old_state_.t, x_old);
  if (is_static_) {
    state_.x = x_;
    state_.t = t_new_;
  } else {
    integrator_->end_step(x_, state_);
  }
  // Energy bookkeeping (trapezoidal): external work and damping dissipation.
  const Vec fext_new = external_force(state_.t, state_.x);
  work_ext_ += 0.5 * (fext_old + fext_new).dot(state_.x - x_old);
  if (f_iface_.size() == body_->num_dofs()) {  // work of the interface forces (trapezoidal)
    if (f_iface_old_.size() != f_iface_.size()) f_iface_old_ = Vec::Zero(f_iface_.size());
    const double w = 0.5 * (f_iface_old_ + f_iface_).dot(state_.x - x_old);
    work_ext_ += w;
    work_iface_ += w;
    f_iface_old_ = f_iface_;
  }
  x_aug_prev_.resize(0);
  if (!is_static_ && (damp_mass_ > 0 || damp_stiff_ > 0)) {
    // Newmark's discrete dissipation: dt v_mid^T C v_mid with v_mid = (v_n + v_{n+1})/2 (exact balance
    // for linear problems; the trapezoid of v^T C v would count high modes that flip sign every step).
    const Vec vmid = 0.5 * (old_state_.v + state_.v);
    work_damp_ += dt_ * vmid.dot(damping_times(vmid));
  }
  Vec f;
  strain_energy_ = body_->internal_force(state_.x, f, nullptr);
  if (need_reaction_) {
    reaction_ = f - fext_new;
    if (f_iface_.size() == reaction_.size()) reaction_ -= f_iface_;
    if (!is_static_) reaction_ += body_->mass() * state_.a + damping_times(state_.v);
  }
  times_.assembly += seconds_since(t0);
}

void SolidModel::write_output(double t) {
  auto t0 = SteadyClock::now();
  if (!series_) series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_);
  body_->write_output(*series_, t, state_);
  times_.output += seconds_since(t0);
}

void SolidModel::serialize(StateArchive& ar) {
  // The state (x, v, a, t) and what the next step reads of the last one; the integrators keep nothing
  // between steps (begin_step takes the state).
  ar.section("solid " + name_);
  ar.io(state_.t, state_.x, state_.v, state_.a);
  ar.io(strain_energy_, work_ext_, work_damp_, energy0_, work_iface_);
  ar.io(f_iface_, f_iface_old_, reaction_, aug_factor_);
  // A factorization that failed once switched the body to LU for the rest of the run.
  std::string solver = solver_settings_.type;
  ar.io(solver, fallback_note_);
  if (ar.loading() && solver != solver_settings_.type) {
    solver_settings_.type = solver;
    make_solver();
  }
  serialize_series(ar, series_, ctx_.out_dir, name_);
}

// ------------------------------------------------------------------------------------------ coupling

std::vector<std::vector<Index>> SolidModel::selected_surface_edges(Params select) const {
  const auto sel = select_nodes(select, surface_reference_);
  const std::set<Index> in(sel.begin(), sel.end());
  std::vector<std::vector<Index>> chosen;
  for (const auto& e : body_->surface_edges())
    if (std::all_of(e.begin(), e.end(), [&](Index n) { return in.count(n) > 0; })) chosen.push_back(e);
  return chosen;
}

InterfaceBoundary SolidModel::make_interface(Params select) const {
  // Interface "nodes" are surface points (a continuum's boundary nodes, a shell's face points).
  InterfaceBoundary ib;
  ib.edges = selected_surface_edges(select);
  if (ib.edges.empty()) select.fail("the selection contains no boundary edge of body '" + name_ + "'");
  std::set<Index> used;
  for (const auto& e : ib.edges) used.insert(e.begin(), e.end());
  ib.nodes.assign(used.begin(), used.end());
  for (Index n : ib.nodes) ib.reference.push_back(surface_reference_[n]);
  return ib;
}

void SolidModel::set_interface_forces(const std::vector<Index>& points, const Vec& forces) {
  if (is_static_) throw SolverError("body '" + name_ + "': interface forces need a dynamic analysis");
  f_iface_ = Vec::Zero(body_->num_dofs());
  body_->add_surface_forces(points, forces, f_iface_);
}

void SolidModel::restart_step() {
  // Newton restarts from the last iterate (it converges to the same solution from any nearby start, and
  // the last coupling iterate is the best guess); the augmented mass measures motion from it.
  x_aug_prev_ = x_;
  last_increment_ = std::numeric_limits<double>::infinity();
  last_residual_ = std::numeric_limits<double>::infinity();
}

void SolidModel::interface_kinematics(const std::vector<Index>& points, const Vec& x, Vec& v, Vec& a) const {
  // The integrator's update of v_{n+1} and a_{n+1} is affine in x_{n+1} with the same coefficients for every
  // dof, so a surface point (a linear combination of dofs) at position x moves with the velocity at the current
  // iterate plus dv/dx times the position difference. dv/dx and da/dx are those of the update itself (not the
  // tangent coefficients, which are the evaluation point's: (1 - alpha) times them in generalized-alpha), read
  // off two updates one unit apart.
  KinematicState s, s1;
  integrator_->end_step(x_, s);
  integrator_->end_step(x_ + Vec::Ones(x_.size()), s1);
  const double dvdx = s1.v[0] - s.v[0], dadx = s1.a[0] - s.a[0];
  const Vec dx = x - body_->surface_values(points, x_);
  v = body_->surface_values(points, s.v) + dvdx * dx;
  a = body_->surface_values(points, s.a) + dadx * dx;
}

}  // namespace lagfsi::solid

namespace lagfsi {

std::unique_ptr<PhysicsModel> make_solid_model(Params body, const CaseContext& ctx) {
  return std::make_unique<solid::SolidModel>(std::move(body), ctx);
}

}  // namespace lagfsi
