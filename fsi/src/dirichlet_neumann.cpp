#include <lagfsi/element.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/fsi/acceleration.hpp>
#include <lagfsi/fsi/coupling.hpp>
#include <lagfsi/fsi/dirichlet_neumann.hpp>
#include <lagfsi/interface.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace lagfsi::fsi {

namespace {

const KeyTable kCouplingKeys(
    "/couplings/* (type dirichlet_neumann)",
    "Strong Dirichlet-Neumann coupling of a fluid body and a structure (solid or shell) through ghost particles.",
    {{"name", "fsi", "Coupling name (probes refer to it)."},
     {"type", "dirichlet_neumann", "`dirichlet_neumann`."},
     {"fluid", nullptr, "Name of the fluid body."},
     {"structure", nullptr, "Name of the structure (a solid or shell body)."},
     {"interface", nullptr,
      "The structure's wet boundary nodes (see selection (type point) and others); edges whose nodes are all "
      "selected carry ghost particles."},
     {"ghost_spacing", 0.0, "Ghost particles along the interface at this spacing (m); 0: one at each node."},
     {"acceleration", Json{{"type", "aitken"}},
      "Acceleration of the iterations (see /couplings/*/acceleration (type aitken) and others)."},
     {"max_iterations", 50, "Coupling passes before the step fails (and is retried at half dt)."},
     {"tolerance", 1e-6,
      "Converged when the interface positions change by less than this times the step's interface motion."},
     {"reference_floor", 1e-9, "Smallest interface motion (m) the change is compared with."},
     {"augmented_mass", 1.0,
      "Augmented-mass factor of the structure (>= 1, 1: off; > 1 with constant relaxation only)."},
     {"predictor", "extrapolation",
      "First guess of the interface: extrapolation (the last step's motion repeated) or forces (the structure "
      "solved under the last step's interface forces)."}});

const KeyTable kInterfaceForceProbeKeys("/probes/* (coupling, type interface_force)",
                                        "The total force (N) of the fluid on the structure.",
                                        probe_keys({"interface_force"}, {{"component", "x", "x or y."}}));

const KeyTable kIterationsProbeKeys("/probes/* (coupling, type iterations)", "The coupling passes of the step.",
                                    probe_keys({"iterations"}, {}));

class DirichletNeumann;

class CouplingProbe final : public Probe {
 public:
  CouplingProbe(const DirichletNeumann& c, std::string name, std::string type, int comp)
      : c_(c), name_(std::move(name)), type_(std::move(type)), comp_(comp) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const DirichletNeumann& c_;
  std::string name_, type_;
  int comp_;
};

class DirichletNeumann final : public PhysicsModel {
 public:
  DirichletNeumann(Params p, const CaseContext& ctx, PhysicsModel& fluid, PhysicsModel& structure);
  std::string name() const override { return name_; }
  std::string type() const override { return "dirichlet_neumann"; }
  Index num_nodes() const override { return 0; }
  Index num_elements() const override { return 0; }
  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  void finalize_step() override;
  void write_output(double) override {}
  std::unique_ptr<Probe> make_probe(Params p) override;
  /// Iterations of the last step's loop (0: the bodies were apart) and its final relative interface residual.
  int coupling_iterations() const { return last_iterations_; }
  /// log.csv: the step's coupling iterations (fsi_iterations, shown in the progress line) and final relative
  /// interface residual (fsi_residual); two couplings add their iterations and keep the larger residual.
  std::vector<Metric> step_metrics() const override {
    return {{"fsi_iterations", double(last_iterations_), Metric::Combine::sum, "fsi"},
            {"fsi_residual", last_residual_, Metric::Combine::max}};
  }
  /// summary.json: the steps that iterated (coupled_steps), their iterations (total, mean, max), the largest
  /// final interface residual and the loops restarted with the accelerator's memory cleared.
  Json summary() const override {
    return {{"coupled_steps", coupled_steps_},
            {"restarts", restarts_},
            {"iterations_total", iterations_total_},
            {"iterations_mean", coupled_steps_ ? double(iterations_total_) / coupled_steps_ : 0.0},
            {"iterations_max", iterations_max_},
            {"residual_max", residual_max_}};
  }
  bool can_checkpoint() const override { return true; }
  /// The loop's memory between steps: the last motion and step (the first guess), the forces of the last
  /// solve (the "forces" predictor, the probes), the accelerator's columns or Jacobian, the counters.
  void serialize(StateArchive& ar) override {
    ar.section("coupling " + name_);
    ar.io(t_new_, dt_, restarts_, last_motion_, dt_prev_, last_iterations_, last_residual_, node_forces_);
    ar.io(coupled_steps_, iterations_total_, iterations_max_, residual_max_);
    ar.section("acceleration " + acceleration_->type());
    acceleration_->serialize(ar);
  }

  Vec2 total_interface_force() const {
    Vec2 f = Vec2::Zero();
    for (Index k = 0; k + 1 < node_forces_.size(); k += 2) f += node_forces_.segment<2>(k);
    return f;
  }

 private:
  /// Prescribes the ghosts from interface node positions x and re-solves the fluid; returns node forces.
  Vec solve_fluid(const Vec& x);
  /// Loads the structure with node forces f and re-solves it (from its last iterate when `restart`, which
  /// also sets the augmented mass's reference); returns its interface node positions.
  Vec solve_structure(const Vec& f, bool restart = true);

  std::string name_;
  CaseContext ctx_;
  PhysicsModel& fluid_model_;
  PhysicsModel& structure_model_;
  InterfaceFluid* fluid_ = nullptr;
  InterfaceStructure* structure_ = nullptr;
  InterfaceBoundary boundary_;
  std::unique_ptr<InterfaceMap> map_;
  std::unique_ptr<Acceleration> acceleration_;
  CouplingSettings settings_;
  double t_new_ = 0, dt_ = 0;
  int inner_ = 0;
  int restarts_ = 0;      // coupled steps whose loop was restarted with the accelerator's memory cleared
  int fluid_passes_ = 0;  // fluid solves of the current loop
  Vec last_motion_;       // interface motion of the last step (x_n - x_{n-1}), for the first guess
  double dt_prev_ = 0;
  bool force_predictor_ = false;  // first guess from the structure under the last interface forces
  int last_iterations_ = 0;
  double last_residual_ = 0;
  // Over the run's accepted steps that iterated: their count, iterations, largest iterations and residual.
  int coupled_steps_ = 0;
  long iterations_total_ = 0;
  int iterations_max_ = 0;
  double residual_max_ = 0;
  Vec node_forces_;  // forces of the fluid on the interface nodes (last solve)
};

std::string fmt(double x, int prec = 6) {
  std::ostringstream o;
  o << std::setprecision(prec) << x;
  return o.str();
}

DirichletNeumann::DirichletNeumann(Params p, const CaseContext& ctx, PhysicsModel& fluid, PhysicsModel& structure)
    : ctx_(ctx), fluid_model_(fluid), structure_model_(structure) {
  p.validate(kCouplingKeys);
  name_ = p.identifier("name");
  fluid_ = dynamic_cast<InterfaceFluid*>(&fluid);
  structure_ = dynamic_cast<InterfaceStructure*>(&structure);
  if (!fluid_) p.fail("fluid", "body '" + fluid.name() + "' is a " + fluid.type() + ", not a fluid");
  if (!structure_)
    p.fail("structure", "body '" + structure.name() + "' is a " + structure.type() + ", not a structure");
  if (ctx.analysis.type != "dynamic") p.fail("type", "a coupling needs a dynamic analysis");
  settings_.max_iterations = p.integer("max_iterations", 1);
  settings_.tolerance = p.positive("tolerance");
  settings_.reference_floor = p.positive("reference_floor");
  const double aug = p.number("augmented_mass");
  if (!(aug >= 1.0)) p.fail("augmented_mass", "must be at least 1 (1: off)");
  structure_->set_augmented_mass(aug);
  acceleration_ = make_acceleration(p.at("acceleration"));
  force_predictor_ = p.choice("predictor", {"forces", "extrapolation"}) == "forces";
  // The augmented term measures the structure's motion from its own last iterate, so with it a coupling pass
  // is not a function of the interface position alone; Aitken's and the quasi-Newton models are built on
  // such pairs and break (cases/studies/added_mass: too slow or divergent at every density ratio).
  if (aug > 1.0 && acceleration_->type() != "constant")
    p.fail("augmented_mass", "works with constant relaxation only (with " + acceleration_->type() +
                                 " a coupling pass would depend on the structure's previous iterate)");

  boundary_ = structure_->make_interface(p.at("interface"));
  // The fluid compares ghosts with its particles pairwise when it takes them in (a 5 km thick shell's edges
  // at 2.5 mm gave millions of ghosts and an initialisation that did not end; 1e-9 m ran out of memory).
  try {
    map_ = std::make_unique<InterfaceMap>(boundary_, p.non_negative("ghost_spacing"));
  } catch (const std::length_error& e) {
    p.fail("ghost_spacing", std::string(e.what()) + ": the spacing is too small for the interface's length");
  }
  try {
    fluid_->add_ghosts(map_->reference(), map_->adjacent());
  } catch (const std::invalid_argument& e) {
    p.fail("fluid", e.what());
  }
  node_forces_ = Vec::Zero(2 * static_cast<Index>(boundary_.nodes.size()));
}

void DirichletNeumann::initialize() {
  // The bodies are initialized by the driver; the ghosts start where the structure is, at rest with it.
  const Vec x = structure_->interface_positions_old(boundary_.nodes);
  const Vec zero = Vec::Zero(x.size());
  fluid_->set_ghost_motion(map_->to_ghosts(x), map_->to_ghosts(zero), map_->to_ghosts(zero));
}

void DirichletNeumann::predict(double t_new, double dt) {
  t_new_ = t_new;
  dt_ = dt;
  structure_model_.predict(t_new, dt);
  fluid_model_.predict(t_new, dt);
  inner_ = 0;
}

Vec DirichletNeumann::solve_fluid(const Vec& x) {
  ++fluid_passes_;
  Vec v, a;
  structure_->interface_kinematics(boundary_.nodes, x, v, a);
  fluid_->set_ghost_motion(map_->to_ghosts(x), map_->to_ghosts(v), map_->to_ghosts(a));
  fluid_->restart_step();
  inner_ += iterate_to_convergence(fluid_model_, ctx_.analysis.newton.max_iterations, t_new_);
  node_forces_ = map_->to_nodes(fluid_->ghost_forces());
  return node_forces_;
}

Vec DirichletNeumann::solve_structure(const Vec& f, bool restart) {
  structure_->set_interface_forces(boundary_.nodes, f);
  if (restart) structure_->restart_step();
  inner_ += iterate_to_convergence(structure_model_, ctx_.analysis.newton.max_iterations, t_new_);
  return structure_->interface_positions(boundary_.nodes);
}

IterationReport DirichletNeumann::solve_iteration() {
  IterationReport rep;
  rep.converged = true;
  rep.increment_ref = 1;
  if (!fluid_->in_contact()) {
    // Apart: the structure alone, then the fluid with the ghosts where it went (they may touch next step).
    node_forces_.setZero();
    const Vec x = solve_structure(node_forces_, false);
    solve_fluid(x);
    node_forces_.setZero();
    last_iterations_ = 0;
    last_residual_ = 0;
    rep.inner_iterations = inner_;
    return rep;
  }
  // First interface guess. "forces": the structure solved under the last step's interface forces (its own
  // dynamics with the load it last had): 4-14 % fewer coupling passes than extrapolating on the FSI cases, for
  // one more structure solve per step, a gain when a fluid pass costs much more than a structure solve (the
  // monolithic fluid), not with the fractional step's cheap re-solves. "extrapolation" (default): the last
  // step's motion repeated,
  // x_n + (dt / dt_prev)(x_n - x_{n-1}) (the structure's own predictor, x_n, starts every loop one step's
  // motion away; extrapolating with v_n and a_n of the trapezoidal rule, which alternate after an impact,
  // sent the first pass far off).
  settings_.origin = structure_->interface_positions_old(boundary_.nodes);
  Vec x0 = settings_.origin;
  if (force_predictor_)
    x0 = solve_structure(node_forces_, false);
  else if (last_motion_.size() == x0.size() && dt_prev_ > 0)
    x0 += (dt_ / dt_prev_) * last_motion_;
  CouplingReport cr;
  int passes = 0;
  for (int attempt = 0;; ++attempt) {
    // A loop that fails after its first pass (a sub-solver throws on an accelerated iterate, or no
    // convergence) is run once more from the same first guess with the accelerator's memory cleared: a
    // quasi-Newton model built on earlier steps' meshes and contact states can send an iterate far off at an
    // impact. A failure of the first pass (the first guess: nothing accelerated yet) or of the second loop
    // goes to the driver, which retries the step with dt/2.
    Vec x = x0;
    fluid_passes_ = 0;
    try {
      cr = dirichlet_neumann_step([this](const Vec& xi) { return solve_fluid(xi); },
                                  [this](const Vec& f) { return solve_structure(f); }, *acceleration_, x, settings_);
      passes += cr.iterations;
      if (cr.converged || attempt > 0) break;
    } catch (const SolverError&) {
      if (attempt > 0 || fluid_passes_ <= 1) throw;
      passes += fluid_passes_;
    }
    ++restarts_;
    acceleration_->reset();
    structure_model_.predict(t_new_, dt_);
  }
  cr.iterations = passes;
  last_iterations_ = cr.iterations;
  last_residual_ = cr.residual / std::max(cr.reference, 1e-300);
  if (!cr.converged)
    throw SolverError("coupling '" + name_ + "': the interface did not converge in " + std::to_string(cr.iterations) +
                      " iterations at t = " + fmt(t_new_) + " (relative residual " + fmt(last_residual_, 3) + ")");
  rep.residual = last_residual_;
  rep.residual_ref = 1;
  rep.inner_iterations = inner_;
  return rep;
}

void DirichletNeumann::finalize_step() {
  const Vec x_old = structure_->interface_positions_old(boundary_.nodes);
  last_motion_ = structure_->interface_positions(boundary_.nodes) - x_old;
  dt_prev_ = dt_;
  if (last_iterations_ > 0) {
    ++coupled_steps_;
    iterations_total_ += last_iterations_;
    iterations_max_ = std::max(iterations_max_, last_iterations_);
    residual_max_ = std::max(residual_max_, last_residual_);
  }
  structure_model_.finalize_step();
  fluid_model_.finalize_step();
}

std::unique_ptr<Probe> DirichletNeumann::make_probe(Params p) {
  const std::string t = p.choice("type", {"interface_force", "iterations"});
  if (t == "interface_force") {
    p.validate(kInterfaceForceProbeKeys);
    return std::make_unique<CouplingProbe>(*this, p.string("name"), t,
                                           p.choice("component", {"x", "y"}) == "x" ? 0 : 1);
  }
  p.validate(kIterationsProbeKeys);
  return std::make_unique<CouplingProbe>(*this, p.string("name"), t, 0);
}

std::vector<double> CouplingProbe::sample() const {
  if (type_ == "iterations") return {double(c_.coupling_iterations())};
  return {c_.total_interface_force()[comp_]};
}

}  // namespace

InterfaceMap::InterfaceMap(const InterfaceBoundary& boundary, double spacing)
    : nodes_(static_cast<Index>(boundary.nodes.size())) {
  std::map<Index, Index> local;  // global node -> interface index
  for (size_t k = 0; k < boundary.nodes.size(); ++k) local[boundary.nodes[k]] = static_cast<Index>(k);
  auto index_of = [&](Index node) {
    const auto it = local.find(node);
    if (it == local.end())
      throw std::invalid_argument("interface edge node " + std::to_string(node) + " is not an interface node");
    return it->second;
  };
  if (spacing == 0) {
    // Matching interface: one ghost per node; neighbours along each edge.
    for (size_t k = 0; k < boundary.nodes.size(); ++k) {
      ghosts_.push_back({{static_cast<Index>(k), 1.0}});
      reference_.push_back(boundary.reference[k]);
    }
    for (const auto& e : boundary.edges)
      for (size_t j = 0; j + 1 < e.size(); ++j) adjacent_.push_back({index_of(e[j]), index_of(e[j + 1])});
    return;
  }
  // Non-matching: ghosts along each edge at about `spacing`; the ones at a vertex are shared. The pieces of
  // every edge are counted first, in double, so that a spacing far too small for the interface is refused
  // before any ghost is made (1e-9 m ran out of memory).
  std::vector<double> pieces;
  double total = 0;
  for (const auto& e : boundary.edges) {
    double length = 0;
    for (size_t j = 0; j + 1 < e.size(); ++j)
      length += (boundary.reference[index_of(e[j + 1])] - boundary.reference[index_of(e[j])]).norm();
    pieces.push_back(std::max(1.0, std::ceil(length / spacing - 1e-9)));
    total += pieces.back();
  }
  if (!(total <= 1e5)) throw std::length_error("more than 100 000 ghost particles (about " + fmt(total, 3) + ")");
  std::map<Index, Index> at_vertex;  // global vertex node -> ghost
  for (size_t ei = 0; ei < boundary.edges.size(); ++ei) {
    const auto& e = boundary.edges[ei];
    const int order = static_cast<int>(e.size()) - 1;
    const int n = static_cast<int>(pieces[ei]);
    Index previous = -1;
    for (int k = 0; k <= n; ++k) {
      Index g = -1;
      const Index vertex = k == 0 ? e.front() : (k == n ? e.back() : -1);
      if (vertex >= 0 && at_vertex.count(vertex)) g = at_vertex[vertex];
      if (g < 0) {
        std::vector<std::pair<Index, double>> w;
        Vec2 X = Vec2::Zero();
        Eigen::VectorXd N, dN;  // the edge's own shape functions, nodes from its first vertex to its second
        line_shape(order, double(k) / n, N, dN);
        for (int j = 0; j <= order; ++j) {
          if (std::abs(N[j]) < 1e-14) continue;
          w.push_back({index_of(e[j]), N[j]});
          X += N[j] * boundary.reference[index_of(e[j])];
        }
        g = static_cast<Index>(ghosts_.size());
        ghosts_.push_back(std::move(w));
        reference_.push_back(X);
        if (vertex >= 0) at_vertex[vertex] = g;
      }
      if (previous >= 0) adjacent_.push_back({previous, g});
      previous = g;
    }
  }
}

Vec InterfaceMap::to_ghosts(const Vec& nodal) const {
  Vec out = Vec::Zero(2 * num_ghosts());
  for (size_t g = 0; g < ghosts_.size(); ++g)
    for (const auto& [a, w] : ghosts_[g]) out.segment<2>(2 * g) += w * nodal.segment<2>(2 * a);
  return out;
}

Vec InterfaceMap::to_nodes(const Vec& ghost) const {
  Vec out = Vec::Zero(2 * nodes_);
  for (size_t g = 0; g < ghosts_.size(); ++g)
    for (const auto& [a, w] : ghosts_[g]) out.segment<2>(2 * a) += w * ghost.segment<2>(2 * g);
  return out;
}

std::unique_ptr<PhysicsModel> make_dirichlet_neumann(Params p, const CaseContext& ctx, PhysicsModel& fluid,
                                                     PhysicsModel& structure) {
  return std::make_unique<DirichletNeumann>(std::move(p), ctx, fluid, structure);
}

}  // namespace lagfsi::fsi
