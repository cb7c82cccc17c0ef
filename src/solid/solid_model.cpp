// The solid body as a PhysicsModel: boundary conditions, loads, Newton iterations with a time integrator
// (or load stepping for static analysis), probes and output.
#include <lagfsi/case.hpp>
#include <lagfsi/element.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/shell.hpp>
#include <lagfsi/solid.hpp>
#include <lagfsi/time_function.hpp>
#include <lagfsi/time_integrator.hpp>
#include <lagfsi/vtk_output.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <set>

namespace lagfsi {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

class SolidModel;

class DisplacementProbe final : public Probe {
 public:
  DisplacementProbe(const SolidModel& m, std::string name, std::vector<std::pair<Index, double>> weights,
                    std::string comp, bool position)
      : m_(m), name_(std::move(name)), weights_(std::move(weights)), comp_(std::move(comp)), position_(position) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_;
  std::vector<std::pair<Index, double>> weights_;
  std::string comp_;
  bool position_;
};

class ReactionProbe final : public Probe {
 public:
  ReactionProbe(const SolidModel& m, std::string name, std::vector<Index> nodes, int comp)
      : m_(m), name_(std::move(name)), nodes_(std::move(nodes)), comp_(comp) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_;
  std::vector<Index> nodes_;
  int comp_;
};

class EnergyProbe final : public Probe {
 public:
  EnergyProbe(const SolidModel& m, std::string name, std::string kind)
      : m_(m), name_(std::move(name)), kind_(std::move(kind)) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_, kind_;
};

class SolidModel final : public PhysicsModel, public InterfaceStructure {
 public:
  SolidModel(Params body, const CaseContext& ctx);

  std::string name() const override { return name_; }
  std::string type() const override { return type_; }
  Index num_nodes() const override { return body_->num_nodes(); }
  Index num_elements() const override { return body_->num_elements(); }
  Json summary() const override {
    return fallback_note_.empty() ? Json::object() : Json{{"linear_solver_fallback", fallback_note_}};
  }

  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  IterationReport newton_iteration();   // solve_iteration without the body's name on its errors
  void finalize_step() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;

  // InterfaceStructure (interface.hpp)
  InterfaceBoundary make_interface(Params select) const override;
  void set_interface_forces(const std::vector<Index>& nodes, const Vec& forces) override;
  void restart_step() override;
  void set_augmented_mass(double factor) override { aug_factor_ = factor; }
  void interface_kinematics(const std::vector<Index>& nodes, const Vec& x, Vec& v, Vec& a) const override;
  Vec interface_positions(const std::vector<Index>& points) const override {
    return body_->surface_values(points, x_);
  }
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
  Vec damping_times(const Vec& v) const;
  std::string name_, type_;
  CaseContext ctx_;
  bool is_static_;
  std::unique_ptr<StructuralBody> body_;
  std::vector<Vec2> surface_reference_;  // reference positions of the body's surface points
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;
  std::string solver_type_;
  double damp_mass_ = 0, damp_stiff_ = 0;
  SparseMatrix K0_;           // initial tangent (stiffness-proportional damping)
  std::vector<Load> loads_;
  std::vector<Prescribed> prescribed_;
  std::vector<char> fixed_mask_;
  double length_ = 1;         // body size, for the position tolerance

  KinematicState state_, old_state_;
  Vec x_;                     // current iterate of x_{n+1}
  double t_new_ = 0, dt_ = 0;
  double last_increment_ = 0;  // |dx| of the last correction of this step (inf before the first)
  double last_residual_ = 0;   // residual norm of the previous iteration of this step
  SparseMatrix H_;
  Vec f_int_;
  double strain_energy_ = 0, work_ext_ = 0, work_damp_ = 0, energy0_ = 0;
  bool need_reaction_ = false;
  Vec reaction_;
  std::unique_ptr<PvdSeries> series_;
  std::string fallback_note_;   // why and when the solver switched to LU (summary.json; a warning unless --quiet)
  // Partitioned coupling: interface forces of the step (and of the last step, for the work), augmented mass.
  Vec f_iface_, f_iface_old_;
  double work_iface_ = 0;  // part of work_ext_ done by the interface forces
  double aug_factor_ = 1.0;
  Vec x_aug_prev_;
};

// ------------------------------------------------------------------------------------------ building

namespace {

/// The reference mid-line of a shell body: {"type": "line", "from", "to"} or {"type": "polyline",
/// "points"}, cut into elements of the mesh's order by "elements" (a line) or "size" (each segment into
/// ceil(length / size) elements).
std::vector<Vec2> shell_midline(Params geo, Params mesh, int& order) {
  if (!geo.json().is_object() || !geo.has("type")) geo.fail("type", "required key is missing");
  const std::string gt = geo.choice("type", {"line", "polyline"});
  std::vector<Vec2> corners;
  if (gt == "line") {
    geo.validate({{"type", "line"}, {"from", nullptr}, {"to", nullptr}});
    corners = {geo.vec2("from"), geo.vec2("to")};
  } else {
    geo.validate({{"type", "polyline"}, {"points", nullptr}});
    corners = geo.points("points");
    if (corners.size() < 2) geo.fail("points", "a polyline needs at least two points");
  }
  mesh.validate({{"order", 3}, {"elements", 0}, {"size", 0.0}});
  order = mesh.integer("order", 1);
  if (order > 3) mesh.fail("order", "must be 1, 2 or 3");
  const int nel = mesh.integer("elements", 0);
  const double size = mesh.non_negative("size");
  if ((nel > 0) == (size > 0)) mesh.fail("give either \"elements\" or \"size\"");
  if (nel > 0 && corners.size() != 2) mesh.fail("elements", "is for a line; give \"size\" for a polyline");
  std::vector<Vec2> nodes{corners[0]};
  for (size_t k = 0; k + 1 < corners.size(); ++k) {
    const Vec2 a = corners[k], b = corners[k + 1];
    const double len = (b - a).norm();
    if (!(len > 0.0)) geo.fail("segment " + std::to_string(k) + " has zero length");
    const int ne = nel > 0 ? nel : std::max(1, static_cast<int>(std::ceil(len / size - 1e-9)));
    for (int i = 1; i <= ne * order; ++i) nodes.push_back(a + (b - a) * (static_cast<double>(i) / (ne * order)));
  }
  return nodes;
}

}  // namespace

SolidModel::SolidModel(Params b, const CaseContext& ctx) : ctx_(ctx), is_static_(ctx.analysis.type == "static") {
  type_ = b.string("type");
  const bool shell = type_ == "shell";
  Json defaults{{"name", nullptr},
                {"type", type_},
                {"material", nullptr},
                {"thickness", shell ? Json(nullptr) : Json(1.0)},
                {"damping", Json::object()},
                {"geometry", nullptr},
                {"mesh", nullptr},
                {"initial_velocity", Json::array({0.0, 0.0})},
                {"boundary_conditions", Json::array()},
                {"loads", Json::array()},
                {"gravity", true}};
  if (shell) {
    defaults["width"] = 1.0;
    defaults["shear_correction"] = 5.0 / 6.0;
    defaults["shear_integration"] = "reduced";
  }
  b.validate(defaults);
  name_ = b.identifier("name");

  Params mat = b.at("material");
  mat.validate({{"type", "svk"}, {"young", nullptr}, {"poisson", 0.0}, {"density", nullptr},
                {"hypothesis", "plane_strain"}});
  const double E = mat.positive("young"), nu = mat.number("poisson"), rho = mat.positive("density");
  if (!(nu > -1.0 && nu < 0.5)) mat.fail("poisson", "must lie in (-1, 0.5)");
  const std::string hyp_name = mat.choice("hypothesis", {"plane_strain", "plane_stress"});
  const double thickness = b.positive("thickness");
  if (shell) {
    if (mat.choice("type", {"svk"}) != "svk") mat.fail("type", "shells use the svk law in their own frame");
    ShellSection sec;
    sec.thickness = thickness;
    sec.width = b.positive("width");
    sec.young = E;
    sec.poisson = nu;
    sec.density = rho;
    sec.plane_strain = hyp_name == "plane_strain";
    sec.shear_correction = b.positive("shear_correction");
    sec.reduced_shear = b.choice("shear_integration", {"reduced", "full"}) == "reduced";
    int order = 3;
    std::vector<Vec2> midline = shell_midline(b.at("geometry"), b.at("mesh"), order);
    try {
      body_ = std::make_unique<ShellBody>(order, std::move(midline), sec);
    } catch (const std::invalid_argument& e) {
      b.fail("geometry", e.what());
    }
  } else {
    const auto hyp = hyp_name == "plane_strain" ? PlaneHypothesis::PlaneStrain : PlaneHypothesis::PlaneStress;
    std::shared_ptr<SolidMaterial> material;
    try {
      material = make_solid_material(mat.choice("type", {"svk", "neo_hookean"}), E, nu, rho, hyp);
    } catch (const std::invalid_argument& e) {
      mat.fail("type", e.what());
    }
    TriMesh mesh = build_mesh(b.at("geometry"), b.at("mesh"));
    try {
      body_ = std::make_unique<SolidBody>(std::move(mesh), material, thickness);
    } catch (const std::exception& e) {
      b.fail("mesh", e.what());
    }
  }

  Params damp = b.at("damping");
  damp.validate({{"mass", 0.0}, {"stiffness", 0.0}});
  damp_mass_ = damp.non_negative("mass");
  damp_stiff_ = damp.non_negative("stiffness");

  const auto& stations = body_->stations();
  {
    Vec2 lo = stations[0], hi = lo;
    for (const auto& p : stations) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    length_ = (hi - lo).norm();
  }
  const Index nd = body_->num_dofs();

  // Boundary conditions: fixed / prescribed displacement / prescribed velocity of the stations'
  // translations; a shell's rotation (its generalised vector) is held by them too unless "rotation" is
  // "free" ("pinned" is "fixed" with a free rotation).
  Params bcs = b.at("boundary_conditions");
  fixed_mask_.assign(nd, 0);
  for (size_t i = 0; i < bcs.size(); ++i) {
    Params bc = bcs.at(i);
    if (!bc.json().is_object() || !bc.has("type")) bc.fail("type", "required key is missing");
    const std::string t = shell ? bc.choice("type", {"fixed", "pinned", "prescribed_displacement", "prescribed_velocity"})
                                : bc.choice("type", {"fixed", "prescribed_displacement", "prescribed_velocity"});
    Json bdef{{"type", t}, {"select", nullptr}, {"components", "xy"}};
    if (t != "fixed" && t != "pinned") {
      bdef["value"] = nullptr;
      bdef["function"] = Json{{"type", "constant"}};
    }
    if (shell) bdef["rotation"] = t == "pinned" ? "free" : "fixed";
    bc.validate(bdef);
    const std::string comps = bc.choice("components", {"x", "y", "xy"});
    const bool hold_rotation = shell && bc.choice("rotation", {"fixed", "free"}) == "fixed";
    const auto sel = select_nodes(bc.at("select"), stations);
    Vec2 value = Vec2::Zero();
    std::shared_ptr<TimeFunction> fn;
    if (t == "prescribed_displacement" || t == "prescribed_velocity") {
      value = bc.vec2("value");
      fn = make_time_function(bc.at("function"), ctx.base_dir);
    }
    auto hold = [&](Index dof, double amplitude, const std::shared_ptr<TimeFunction>& f) {
      if (fixed_mask_[dof]) return;  // first condition wins
      fixed_mask_[dof] = 1;
      prescribed_.push_back({dof, amplitude, f, t == "prescribed_velocity"});
    };
    for (Index s : sel) {
      for (int c = 0; c < 2; ++c) {
        if ((c == 0 && comps == "y") || (c == 1 && comps == "x")) continue;
        hold(2 * body_->station_node(s) + c, value[c], fn);
      }
      const Index rn = body_->station_rotation_node(s);
      if (hold_rotation && rn >= 0)
        for (int c = 0; c < 2; ++c) hold(2 * rn + c, 0.0, nullptr);
    }
  }

  // A static body must be held: fewer than three fixed components leave a rigid motion free, and the
  // singular tangent would fail at the first Newton step with a less telling message.
  const auto held = std::count(fixed_mask_.begin(), fixed_mask_.end(), 1);
  if (is_static_ && held < 3)
    bcs.fail("a static analysis needs boundary conditions that hold the body (at least 3 fixed components; "
             "this body has " + std::to_string(held) + ")");

  // Loads: point loads (value split equally over the selected stations), tractions and pressures on
  // boundary edges (all of whose points are selected), body forces.
  Params loads = b.at("loads");
  {
    std::vector<Index> all(body_->surface_points().size());
    for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<Index>(k);
    const Vec s = body_->surface_values(all, body_->reference_positions());
    surface_reference_.resize(all.size());
    for (size_t k = 0; k < all.size(); ++k) surface_reference_[k] = s.segment<2>(2 * k);
  }
  auto selected_edges = [&](Params l) {
    auto chosen = selected_surface_edges(l.at("select"));
    if (chosen.empty()) l.fail("select", "the selection contains no boundary edge");
    return chosen;
  };
  for (size_t i = 0; i < loads.size(); ++i) {
    Params l = loads.at(i);
    if (!l.json().is_object() || !l.has("type")) l.fail("type", "required key is missing");
    const std::string t = l.choice("type", {"point_load", "traction", "pressure", "body_force"});
    Json ldef{{"type", t}, {"value", nullptr}, {"function", Json{{"type", "constant"}}}};
    if (t != "body_force") ldef["select"] = nullptr;
    if (t == "pressure") ldef["follower"] = true;
    l.validate(ldef);
    Load load{Vec::Zero(nd), std::shared_ptr<TimeFunction>(make_time_function(l.at("function"), ctx.base_dir)), {}};
    if (t == "pressure") {
      // Pressure p pushes on the boundary: the force is -p n ds (n outward).
      const double p = l.number("value");
      const auto edges = selected_edges(l);
      const SparseMatrix P = follower_pressure_matrix(*body_, edges);
      if (l.boolean("follower"))
        load.follower = p * P;
      else
        load.f = p * (P * body_->reference_positions());
      loads_.push_back(std::move(load));
      continue;
    }
    const Vec2 value = l.vec2("value");
    if (t == "point_load") {
      const auto sel = select_nodes(l.at("select"), stations);
      for (Index n : sel) load.f.segment<2>(2 * body_->station_node(n)) = value / static_cast<double>(sel.size());
    } else if (t == "traction") {
      load.f = surface_traction(*body_, selected_edges(l), value);
    } else {
      load.f = body_->body_force(value);
    }
    loads_.push_back(std::move(load));
  }
  if (b.boolean("gravity") && ctx.gravity.squaredNorm() > 0)
    loads_.push_back({body_->body_force(body_->density() * ctx.gravity), constant_function(1.0), {}});

  // Integrator and solver.
  if (!is_static_) {
    Params ip(ctx.analysis.integrator, ctx.case_file.string(), "/analysis/integrator");
    const std::string it = ip.string("type");
    if (it == "newmark")
      integrator_ = make_newmark(ip.number("beta"), ip.number("gamma"));
    else if (it == "generalized_alpha")
      integrator_ = make_generalized_alpha(ip.number("rho_inf"));
    else
      integrator_ = make_central_difference();
  }
  solver_type_ = ctx.analysis.linear_solver;
  solver_ = make_linear_solver(solver_type_);

  state_.t = 0;
  state_.x = body_->reference_positions();
  state_.v = Vec::Zero(nd);
  const Vec2 v0 = b.vec2("initial_velocity");
  for (Index n = 0; n < body_->num_nodes(); ++n) state_.v.segment<2>(2 * n) = v0;
  for (const auto& p : prescribed_) state_.v[p.dof] = 0.0;
  state_.a = Vec::Zero(nd);
  H_ = body_->pattern();
}

// ------------------------------------------------------------------------------------------ helpers

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

void SolidModel::apply_dirichlet(SparseMatrix& H, Vec& r) const {
  for (int k = 0; k < H.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(H, k); it; ++it)
      if (fixed_mask_[it.row()] || fixed_mask_[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  for (Index i = 0; i < r.size(); ++i)
    if (fixed_mask_[i]) r[i] = 0.0;
}

void SolidModel::factorize(const SparseMatrix& H) {
  try {
    solver_->factorize(H);
  } catch (const SolverError& e) {
    if (solver_type_ != "cholmod" && solver_type_ != "cholmod_supernodal") throw;
    // Non-finite entries are not a matter of definiteness: LU would fail the same way.
    if (!std::all_of(H.valuePtr(), H.valuePtr() + H.nonZeros(), [](double v) { return std::isfinite(v); })) throw;
    // An indefinite tangent (buckling, strong compression): switch to LU for the rest of the run. The
    // warning comes once the LU has factorized, so that a run that fails says it in one line.
    solver_type_ = "umfpack";
    solver_ = make_linear_solver(solver_type_);
    solver_->factorize(H);
    fallback_note_ = std::string(e.what()) + "; switched to umfpack at t = " + std::to_string(t_new_);
    if (!ctx_.quiet) std::cerr << "lagfsi: warning: body '" << name_ << "': " << fallback_note_ << "\n";
  }
}

// ------------------------------------------------------------------------------------------ lifecycle

void SolidModel::initialize() {
  auto t0 = Clock::now();
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
    s->factorize(M);
    s->solve(r, state_.a);
    for (const auto& p : prescribed_) state_.a[p.dof] = 0.0;
  }
  times_.assembly += seconds_since(t0);
}

void SolidModel::predict(double t_new, double dt) {
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
  auto t0 = Clock::now();
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
    // H = c_m M + c_c C + c_k K, all on the same pattern.
    const double* m = body_->mass().valuePtr();
    double* h = H_.valuePtr();
    const double* k0 = damp_stiff_ > 0 ? K0_.valuePtr() : nullptr;
    const double cm = c.c_m * (augmented ? aug_factor_ : 1.0) + c.c_c * damp_mass_;
    for (Index i = 0; i < H_.nonZeros(); ++i) {
      h[i] = c.c_k * h[i] + cm * m[i];
      if (k0) h[i] += c.c_c * damp_stiff_ * k0[i];
    }
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

  t0 = Clock::now();
  factorize(H_);
  times_.factorization += seconds_since(t0);
  t0 = Clock::now();
  Vec dx;
  solver_->solve(-r, dx);
  times_.solve += seconds_since(t0);
  x_ += dx;
  rep.increment = dx.norm();
  last_increment_ = rep.increment;

  if (!x_.allFinite()) throw SolverError("body '" + name_ + "': non-finite positions");
  return rep;
}

void SolidModel::finalize_step() {
  auto t0 = Clock::now();
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
  if (!is_static_ && (damp_mass_ > 0 || damp_stiff_ > 0))
  {
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
  auto t0 = Clock::now();
  if (!series_) series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_);
  body_->write_output(*series_, t, state_);
  times_.output += seconds_since(t0);
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

// ------------------------------------------------------------------------------------------ probes

std::unique_ptr<Probe> SolidModel::make_probe(Params p) {
  const std::string t = p.choice("type", {"displacement", "position", "reaction", "energy"});
  if (t == "displacement" || t == "position") {
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"at", nullptr}, {"component", "y"}});
    const std::string comp = p.choice("component", {"x", "y", "magnitude"});
    std::vector<std::pair<Index, double>> w;
    if (!body_->locate(p.vec2("at"), w)) p.fail("at", "the point is outside body '" + name_ + "'");
    return std::make_unique<DisplacementProbe>(*this, p.string("name"), std::move(w), comp, t == "position");
  }
  if (t == "reaction") {
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"select", nullptr}, {"component", "y"}});
    const int comp = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
    need_reaction_ = true;
    std::vector<Index> nodes;
    for (Index s : select_nodes(p.at("select"), body_->stations())) nodes.push_back(body_->station_node(s));
    return std::make_unique<ReactionProbe>(*this, p.string("name"), std::move(nodes), comp);
  }
  p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"kind", "total"}});
  return std::make_unique<EnergyProbe>(
      *this, p.string("name"),
      p.choice("kind", {"kinetic", "strain", "external_work", "interface_work", "dissipated", "total", "balance"}));
}

std::vector<double> DisplacementProbe::sample() const {
  const Vec& x = m_.state().x;
  const Vec& X = m_.body().reference_positions();
  Vec2 u = Vec2::Zero();
  for (const auto& [node, w] : weights_) {
    const Vec2 d = x.segment<2>(2 * node) - (position_ ? Vec2::Zero() : Vec2(X.segment<2>(2 * node)));
    u += w * d;
  }
  if (comp_ == "x") return {u.x()};
  if (comp_ == "y") return {u.y()};
  return {u.norm()};
}

std::vector<double> ReactionProbe::sample() const {
  const Vec& r = m_.reaction();
  double s = 0.0;
  if (r.size() == 0) return {0.0};
  for (Index n : nodes_) s += r[2 * n + comp_];
  return {s};
}

std::vector<double> EnergyProbe::sample() const {
  if (kind_ == "kinetic") return {m_.kinetic_energy()};
  if (kind_ == "strain") return {m_.strain_energy()};
  if (kind_ == "external_work") return {m_.external_work()};
  if (kind_ == "interface_work") return {m_.interface_work()};
  if (kind_ == "dissipated") return {m_.dissipated()};
  const double total = m_.kinetic_energy() + m_.strain_energy();
  if (kind_ == "total") return {total};
  // balance: E(t) - E(0) - W_ext + W_damp, zero for an exact integrator.
  return {total - m_.initial_energy() - m_.external_work() + m_.dissipated()};
}

}  // namespace

std::unique_ptr<PhysicsModel> make_solid_model(Params body, const CaseContext& ctx) {
  return std::make_unique<SolidModel>(std::move(body), ctx);
}

}  // namespace lagfsi
