#pragma once
/// @file solid_model_impl.hpp (private to src/solid; the public side is src/solid/include/lagfsi/solid/solid_model.hpp)
/// The solid or shell body as a PhysicsModel (SolidModel): its boundary conditions and loads (read by
/// solid_input.cpp), the Newton iterations of a step with a time integrator or load stepping for static
/// analysis (solid_newton.cpp), the lifecycle, output and coupling (solid_model.cpp) and its probes
/// (solid_probes.cpp).
#include <lagfsi/case.hpp>
#include <lagfsi/element.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/linear_solver_input.hpp>
#include <lagfsi/solid/shell.hpp>
#include <lagfsi/solid/solid.hpp>
#include <lagfsi/solid/solid_model.hpp>
#include <lagfsi/stopwatch.hpp>
#include <lagfsi/time_function.hpp>
#include <lagfsi/time_integrator.hpp>
#include <lagfsi/vtk_output.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <set>

namespace lagfsi::solid {

/// A load: a fixed nodal force vector scaled by a function of time (and by the load factor in statics), or
/// a follower pressure whose nodal forces are fn(t) P x (P from follower_pressure_matrix).
struct Load {
  Vec f;
  std::shared_ptr<TimeFunction> fn;
  SparseMatrix follower;  // empty for dead loads
};

/// A prescribed dof: x = X + amplitude * g(t), g = f (displacement) or int f (velocity).
struct Prescribed {
  Index dof;
  double amplitude;
  std::shared_ptr<TimeFunction> fn;  // null: fixed
  bool velocity;
};

class SolidModel final : public PhysicsModel, public InterfaceStructure {
 public:
  SolidModel(Params body, const CaseContext& ctx);

  std::string name() const override { return name_; }
  std::string type() const override { return type_; }
  Index num_nodes() const override { return body_->num_nodes(); }
  Index num_elements() const override { return body_->num_elements(); }
  Json summary() const override {
    Json s = {{"linear_solver", solver_summary(*solver_)}};
    if (!fallback_note_.empty()) s["linear_solver_fallback"] = fallback_note_;
    return s;
  }

  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  IterationReport newton_iteration();  // solve_iteration without the body's name on its errors
  void finalize_step() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;
  bool can_checkpoint() const override { return true; }
  void serialize(StateArchive& ar) override;

  // InterfaceStructure (interface.hpp)
  InterfaceBoundary make_interface(Params select) const override;
  void set_interface_forces(const std::vector<Index>& nodes, const Vec& forces) override;
  void restart_step() override;
  void set_augmented_mass(double factor) override { aug_factor_ = factor; }
  void interface_kinematics(const std::vector<Index>& nodes, const Vec& x, Vec& v, Vec& a) const override;
  Vec interface_positions(const std::vector<Index>& points) const override { return body_->surface_values(points, x_); }
  Vec interface_positions_old(const std::vector<Index>& points) const override {
    return body_->surface_values(points, state_.x);
  }

  // Read access for probes.
  const StructuralBody& body() const { return *body_; }
  const KinematicState& state() const { return state_; }
  const Vec& reaction() const { return reaction_; }
  double kinetic_energy() const { return 0.5 * state_.v.dot(body_->mass() * state_.v); }
  double strain_energy() const { return strain_energy_; }
  double external_work() const { return work_ext_; }
  double interface_work() const { return work_iface_; }
  double dissipated() const { return work_damp_; }
  double initial_energy() const { return energy0_; }

 private:
  /// Input stages of the constructor: the material and the solid or shell body, the boundary conditions (which
  /// components are held or prescribed), the loads (point loads, tractions, pressures, body forces, gravity).
  void read_body(Params b);
  void read_boundary_conditions(Params b);
  void read_loads(Params b);

  /// The surface edges all of whose points a selection (select_nodes syntax, on the points' reference
  /// positions) picks; possibly none.
  std::vector<std::vector<Index>> selected_surface_edges(Params select) const;
  /// External force at time t for positions x (follower loads depend on x).
  Vec external_force(double t, const Vec& x) const;
  /// Adds the tangent of the follower loads at time t, scaled by `scale`, to H (same pattern).
  void add_follower_tangent(double t, double scale, SparseMatrix& H) const;
  double load_factor(double t) const { return is_static_ ? t : 1.0; }
  void impose_prescribed(double t, Vec& x) const;
  void apply_dirichlet(SparseMatrix& H, Vec& r) const;
  void factorize(const SparseMatrix& H);
  /// A new solver from solver_settings_ (with the nodes' coordinates for a multigrid).
  void make_solver();
  Vec damping_times(const Vec& v) const;
  std::string name_, type_;
  CaseContext ctx_;
  bool is_static_;
  std::unique_ptr<StructuralBody> body_;
  std::vector<Vec2> surface_reference_;  // reference positions of the body's surface points
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;
  LinearSolverSettings solver_settings_;
  double damp_mass_ = 0, damp_stiff_ = 0;
  SparseMatrix K0_;  // initial tangent (stiffness-proportional damping)
  std::vector<Load> loads_;
  std::vector<Prescribed> prescribed_;
  std::vector<char> fixed_mask_;
  double length_ = 1;  // body size, for the position tolerance

  KinematicState state_, old_state_;
  Vec x_;  // current iterate of x_{n+1}
  double t_new_ = 0, dt_ = 0;
  double last_increment_ = 0;  // |dx| of the last correction of this step (inf before the first)
  double last_residual_ = 0;   // residual norm of the previous iteration of this step
  SparseMatrix H_;
  Vec f_int_;
  double strain_energy_ = 0, work_ext_ = 0, work_damp_ = 0, energy0_ = 0;
  bool need_reaction_ = false;
  Vec reaction_;
  std::unique_ptr<PvdSeries> series_;
  std::string fallback_note_;  // why and when the solver switched to LU (summary.json; a warning unless --quiet)
  // Partitioned coupling: interface forces of the step (and of the last step, for the work), augmented mass.
  Vec f_iface_, f_iface_old_;
  double work_iface_ = 0;  // part of work_ext_ done by the interface forces
  double aug_factor_ = 1.0;
  Vec x_aug_prev_;
};

}  // namespace lagfsi::solid
