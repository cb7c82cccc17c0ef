// Material Point Method (single phase, explicit) on a regular background grid, after Sulsky, Chen & Schreyer
// (1994) and the "modified Lagrangian" (MUSL) algorithm of the seed (Ludeña 2016, ch. 3; Al-Kafaji 2013):
//
//   particles -> grid:  m_I = sum_p N_Ip m_p,  (m v)_I = sum_p N_Ip m_p v_p,
//                       f_I = sum_p [ -V_p sigma_p . grad N_Ip + N_Ip m_p g ]
//   grid update:        (m v)_I += dt f_I (fixed components zeroed; local damping f -= alpha |f| sign(v))
//   grid -> particles:  v_p += dt sum_I N_Ip f_I / m_I (FLIP),  x_p += dt sum_I N_Ip v_I
//   stress update:      L_p = sum_I v_I (x) grad N_Ip, F_p = (I + dt L_p) F_p, V_p = det F_p V_p0,
//                       sigma_p += C : dt sym(L_p) (small strain rate, linear elastic)
//
// with the grid velocity of the stress update taken, as chosen by "update":
//  - "musl": re-mapped from the updated particle velocities (the seed's algorithm; the most robust);
//  - "usl":  the grid velocity of the grid update;
//  - "usf":  the stress is updated first, from the grid velocity of the mapped momentum.
// Shape functions: "linear" (tent functions of the cells) or "gimp" (uGIMP: particle domains of half-width
// lp = h / (2 n), n particles per cell per direction, which removes most of the cell-crossing noise;
// Bardenhagen & Kober 2004). Plane strain, unit thickness.
//
// Time: the driver's step is split into sub-steps dt_sub <= cfl h / c, c = sqrt((lambda + 2 mu)/rho) the
// P-wave speed (explicit, conditionally stable; with water, c includes K_w / n). The grid is reset every
// sub-step.
//
// Also here: Mohr-Coulomb plasticity (return_mapping: principal stresses, main plane, edges, apex; Jaumann
// stress rate), the saturated two-phase v-w formulation of the seed (substep_two_phase), Cundall local and
// Rayleigh damping, fixed and prescribed-motion grid nodes (an accelerogram is integrated to the nodes'
// velocity), particle loads, and the probes.
#include <lagfsi/case.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/time_function.hpp>
#include <lagfsi/time_integrator.hpp>
#include <lagfsi/vtk_output.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace lagfsi {

namespace {

using Clock = std::chrono::steady_clock;
using Vec3 = Eigen::Vector3d;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Particles of one body (structure of arrays).
struct Particles {
  std::vector<Vec2> x, X, v;
  std::vector<double> mass, volume0, volume;
  std::vector<Mat2> F;
  std::vector<std::array<double, 4>> stress;  // xx, yy, xy, zz
  std::vector<std::array<double, 3>> strain;  // small strain xx, yy, xy (engineering/2: tensor xy)
  std::vector<double> plastic;                 // accumulated plastic multiplier (equivalent plastic shear)
  std::vector<std::array<double, 3>> rate;     // last strain rate xx, yy, xy
  // Two-phase (saturated) bodies: porosity, water velocity, pore pressure (tension positive, as in the
  // formulation; output as compression-positive "pore_pressure").
  std::vector<double> n, p;
  std::vector<Vec2> w;
  std::vector<Vec2> a;  // last acceleration (grid to particle)
  size_t size() const { return x.size(); }
};

/// Up to 3 x 3 nodes of one particle with their shape function values and gradients.
struct Support {
  int n = 0;
  std::array<Index, 9> node;
  std::array<double, 9> N;
  std::array<Vec2, 9> dN;
};

class MpmModel;

class MpmProbe final : public Probe {
 public:
  MpmProbe(const MpmModel& m, std::string name, std::string quantity, Index particle)
      : m_(m), name_(std::move(name)), quantity_(std::move(quantity)), p_(particle) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;
  void set_line(double x, double band) {
    x_ = x;
    band_ = band;
  }

 private:
  const MpmModel& m_;
  std::string name_, quantity_;
  Index p_;
  double x_ = 0, band_ = 0;
};

class MpmModel final : public PhysicsModel {
 public:
  MpmModel(Params b, const CaseContext& ctx);
  std::string name() const override { return name_; }
  std::string type() const override { return "mpm"; }
  Index num_nodes() const override { return static_cast<Index>(P_.size()); }
  Index num_elements() const override { return static_cast<Index>(nx_ * ny_); }
  void initialize() override;
  void predict(double t_new, double dt) override {
    t_new_ = t_new;
    dt_ = dt;
  }
  IterationReport solve_iteration() override;
  void finalize_step() override {}
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;

  const Particles& particles() const { return P_; }
  double kinetic_energy() const {
    double e = 0;
    for (size_t p = 0; p < P_.size(); ++p) e += 0.5 * P_.mass[p] * P_.v[p].squaredNorm();
    return e;
  }
  /// Elastic strain energy sum_p V_p sigma : eps / 2 (linear elastic, small strain).
  double strain_energy() const {
    double e = 0;
    for (size_t p = 0; p < P_.size(); ++p) {
      const auto& s = P_.stress[p];
      const auto& d = P_.strain[p];
      e += 0.5 * P_.volume[p] * (s[0] * d[0] + s[1] * d[1] + 2.0 * s[2] * d[2]);
    }
    return e;
  }
  /// Work of gravity since the start.
  double gravity_work() const { return gravity_work_; }

 private:
  void support(const Vec2& x, Support& s) const;
  void substep(double dt);
  /// One explicit step of the saturated (v-w) formulation (seed 000 sec. 3.5-3.6; digest 2.8).
  void substep_two_phase(double dt);
  /// One implicit step (the analysis' Newmark or generalized-alpha, the solid's integrator objects) on the
  /// grid: linear elastic, small strain, one linear solve (the problem is linear within the step).
  void step_implicit(double dt);
  /// Supports of every particle at its current position; throws SolverError when one has left the grid.
  void locate_particles();
  /// Linear elastic small-strain update of particle q from the gradient G of its displacement increment: stress,
  /// strain, deformation gradient and volume.
  void elastic_increment(Index q, const Mat2& G) {
    const double dxx = G(0, 0), dyy = G(1, 1), dxy = 0.5 * (G(0, 1) + G(1, 0)), tr = dxx + dyy;
    auto& sg = P_.stress[q];
    sg[0] += lambda_ * tr + 2 * mu_ * dxx;
    sg[1] += lambda_ * tr + 2 * mu_ * dyy;
    sg[2] += 2 * mu_ * dxy;
    sg[3] += lambda_ * tr;
    auto& e = P_.strain[q];
    e[0] += dxx;
    e[1] += dyy;
    e[2] += dxy;
    P_.F[q] = (Mat2::Identity() + G) * P_.F[q];
    const Mat2& F = P_.F[q];
    P_.volume[q] = (F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0)) * P_.volume0[q];
  }
  /// Adds the particle loads at time t to grid forces f.
  void add_loads(std::vector<Vec2>& f, double t) const {
    for (const auto& l : loads_) {
      const Vec2 F = l.fn->value(t) * l.force;
      for (Index q : l.particles) {
        const Support& sp = sup_[q];
        for (int k = 0; k < sp.n; ++k) f[sp.node[k]] += sp.N[k] * F;
      }
    }
  }
  /// Particles to grid: mass and momentum, and/or forces (internal and gravity).
  void scatter(bool momentum, bool force);
  void stress_update(double dt, const std::vector<Vec2>& vgrid);
  void apply_fixed(std::vector<Vec2>& vec) const {
    for (const auto& [node, comp] : fixed_) vec[node][comp] = 0.0;
  }

  std::string name_;
  CaseContext ctx_;
  double rho_ = 0, E_ = 0, nu_ = 0, lambda_ = 0, mu_ = 0;
  bool plastic_ = false;                      // Mohr-Coulomb (else linear elastic)
  double cohesion_ = 0, sin_phi_ = 0, cos_phi_ = 1, sin_psi_ = 0;
  double tension_cutoff_ = std::numeric_limits<double>::infinity();  // at most c cot(phi), the apex
  /// Mohr-Coulomb return mapping of a trial stress (xx, yy, xy, zz); returns the plastic multiplier.
  double return_mapping(std::array<double, 4>& s) const;
  Vec2 origin_ = Vec2::Zero();
  double h_ = 1;
  int nx_ = 0, ny_ = 0, ppc_ = 2;
  bool gimp_ = false;
  std::string update_ = "musl";
  double cfl_ = 0.5, local_damping_ = 0;
  double flip_ = 1.0;  // FLIP share of the particle velocity update (1: FLIP; 0: PIC, the grid velocity)
  double damp_mass_ = 0, damp_stiff_ = 0;  // Rayleigh: alpha M v on the grid, beta C : (strain rate) on the particles
  bool gravity_ = true;
  bool particles_csv_ = false;  // also write <out>/<name>_particles.csv (the particles at the last output)
  std::vector<std::pair<Index, int>> fixed_;  // grid node, component
  /// Grid node components that move with a prescribed velocity: value * f(t), or value * int_0^t f for a
  /// prescribed acceleration f (a base accelerogram).
  struct PrescribedMotion {
    Index node;
    int comp;
    double value;
    std::shared_ptr<TimeFunction> fn;
    bool acceleration;
    double velocity(double t) const { return value * (acceleration ? fn->integral(t) : fn->value(t)); }
  };
  std::vector<PrescribedMotion> moving_;
  /// Viscous absorbing boundary (Lysmer & Kuhlemeyer 1969): dashpots rho c_p on the normal and rho c_s on the
  /// tangential velocity of the selected grid nodes, each over a boundary length of one cell.
  struct Dashpot {
    Index node;
    Vec2 normal;
    double length;  // tributary boundary length: h/2 per neighbouring selected node along the boundary
  };
  std::vector<Dashpot> dashpots_;
  /// Free-field boundary (Zienkiewicz, Bicanic & Shen 1989, "Earthquake input definition and the transmitting
  /// boundary conditions"; as in FLAC and Plaxis): beside a lateral boundary a 1D soil column of the body's
  /// elastic material (per unit width, nodes at the boundary's grid nodes) is shaken by the same base motion
  /// and computed alongside; each boundary node gets the dashpots on its velocity relative to the column's
  /// and the column's stress as a traction, t = sigma_ff n (n outward), sigma_ff = the static stress plus
  /// the column's dynamic stress. The static part is the geostatic K0 sigma_v (start = 0) or, with a start
  /// time, the reactions of rollers that hold the boundary until then (the procedure of FLAC: a static stage
  /// on rollers, then the free field with the rollers' forces; needed when the structure's weight loads the
  /// boundary beyond the far field's geostatic stress). A column of a uniform layer moves as the 1D site
  /// response, so the boundary neither reflects the outgoing waves nor disturbs the incoming ones.
  struct FreeField {
    std::vector<Index> nodes;      // boundary grid nodes from the base up (the column's nodes)
    std::vector<double> length;    // tributary boundary length of each node
    std::vector<double> le;        // column element lengths (node k to k+1; the last may stop at the top)
    std::vector<double> mass;      // column node masses per unit width
    std::vector<double> sv;        // geostatic vertical stress at the nodes (negative below the top)
    std::vector<Vec2> u, v;        // column displacements and velocities (dynamic part)
    std::array<const PrescribedMotion*, 2> base{nullptr, nullptr};  // base motion per component
    std::array<bool, 2> base_fixed{false, false};
    Vec2 normal;                   // outward (+-1, 0)
    double start = 0;              // rollers (fixed x) before this time, then the free field
    std::vector<double> reaction;  // the rollers' last horizontal reactions (the static traction after start)
    bool active(double t) const { return t >= start; }
    /// Dynamic strains of element k (shear gamma_xy, axial eps_yy) plus beta times their rates: the strain
    /// that a stiffness-proportional (Kelvin-Voigt) damping beta adds to the elastic stress.
    Vec2 strain(size_t k, double beta) const { return (u[k + 1] - u[k] + beta * (v[k + 1] - v[k])) / le[k]; }
  };
  std::vector<FreeField> free_fields_;
  double k0_ = 0;  // the K0 of the geostatic initial stress (free-field columns)
  /// Advances the free-field columns by dt (their base moves with the grid's base at t + dt).
  void step_free_fields(double dt);
  /// Adds the free-field columns' stresses as tractions on their boundary nodes' grid forces.
  void add_free_field_tractions();
  /// Adds the dashpot forces of the absorbing and free-field boundaries (implicit in the node's velocity).
  void add_dashpot_forces(double dt);
  bool implicit_ = false;
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;
  double local_until_ = std::numeric_limits<double>::infinity();  // local damping only before this time
  Particles P_;
  // Two-phase: water density, bulk modulus, hydraulic conductivity (m/s); grains incompressible.
  bool two_phase_ = false;
  double rho_w_ = 1000, K_w_ = 2.2e9, k_hyd_ = 1e-3;
  std::vector<double> gms_, gmw_, gmwn_, gq_;      // grid: solid mass, water mass, n * water mass, drag
  std::vector<Vec2> gps_, gpw_, gfs_, gfw_, gvs_, gvw_, gas_, gaw_;
  /// Particle forces (total force split over the selected particles) scaled by a function of time.
  struct ParticleLoad {
    std::vector<Index> particles;
    Vec2 force;
    std::shared_ptr<TimeFunction> fn;
  };
  std::vector<ParticleLoad> loads_;
  std::vector<double> gm_;
  std::vector<Vec2> gp_, gf_, gv_;
  std::vector<Support> sup_;
  std::vector<std::vector<double>> tm_;          // per-thread grid copies of the scatter
  std::vector<std::vector<Vec2>> tp_, tf_;
  double t_new_ = 0, dt_ = 0, t_ = 0;
  double gravity_work_ = 0;
  long substeps_ = 0;
  std::unique_ptr<PvdSeries> series_, grid_series_;
  bool grid_output_ = false;  // also write the grid nodes that carry mass as <name>_grid.pvd
};

// ------------------------------------------------------------------------------------------ building

bool inside_polygon(const std::vector<Vec2>& poly, const Vec2& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

MpmModel::MpmModel(Params b, const CaseContext& ctx) : ctx_(ctx) {
  b.validate({{"name", nullptr},
              {"type", "mpm"},
              {"material", nullptr},
              {"grid", nullptr},
              {"regions", nullptr},
              {"particles_per_cell", 2},
              {"shape_functions", "linear"},
              {"update", "musl"},
              {"cfl", 0.5},
              {"flip", 1.0},
              {"boundary_conditions", Json::array()},
              {"damping", Json::object()},
              {"initial_velocity", Json::array({0.0, 0.0})},
              {"initial_state", Json{{"type", "given"}}},
              {"initial_stress", Json{{"type", "zero"}}},
              {"particles_csv", false},
              {"grid_output", false},
              {"two_phase", Json::object()},
              {"absorbing_boundaries", Json::array()},
              {"time_integration", "explicit"},
              {"loads", Json::array()},
              {"gravity", true}});
  name_ = b.identifier("name");
  if (ctx.analysis.type != "dynamic") b.fail("type", "an MPM body needs a dynamic analysis");
  Params mat = b.at("material");
  if (!mat.json().is_object() || !mat.has("type")) mat.fail("type", "required key is missing");
  plastic_ = mat.choice("type", {"linear_elastic", "mohr_coulomb"}) == "mohr_coulomb";
  if (plastic_) {
    mat.validate({{"type", "mohr_coulomb"}, {"young", nullptr}, {"poisson", 0.0}, {"density", nullptr},
                  {"cohesion", 0.0}, {"friction_angle", nullptr}, {"dilatancy_angle", 0.0},
                  {"tension_cutoff", -1.0}});
    cohesion_ = mat.non_negative("cohesion");
    const double phi = mat.number("friction_angle"), psi = mat.number("dilatancy_angle");
    if (!(phi > 0 && phi < 90)) mat.fail("friction_angle", "must lie in (0, 90) degrees");
    if (!(psi >= 0 && psi <= phi)) mat.fail("dilatancy_angle", "must lie in [0, friction_angle] degrees");
    sin_phi_ = std::sin(phi * M_PI / 180);
    cos_phi_ = std::cos(phi * M_PI / 180);
    sin_psi_ = std::sin(psi * M_PI / 180);
    const double apex = cohesion_ * cos_phi_ / sin_phi_;
    tension_cutoff_ = apex;
    if (mat.number("tension_cutoff") >= 0) {  // -1: at the apex
      tension_cutoff_ = mat.number("tension_cutoff");
      if (tension_cutoff_ > apex) mat.fail("tension_cutoff", "must not exceed c cot(phi) = " + std::to_string(apex) + " Pa");
    }
  } else {
    mat.validate({{"type", "linear_elastic"}, {"young", nullptr}, {"poisson", 0.0}, {"density", nullptr}});
  }
  E_ = mat.positive("young");
  nu_ = mat.number("poisson");
  rho_ = mat.positive("density");
  if (!(nu_ > -1.0 && nu_ < 0.5)) mat.fail("poisson", "must lie in (-1, 0.5)");
  mu_ = E_ / (2 * (1 + nu_));
  lambda_ = E_ * nu_ / ((1 + nu_) * (1 - 2 * nu_));

  Params g = b.at("grid");
  g.validate({{"origin", Json::array({0.0, 0.0})}, {"size", nullptr}, {"cell", nullptr}});
  origin_ = g.vec2("origin");
  const Vec2 size = g.vec2("size");
  h_ = g.positive("cell");
  if (!(size.x() > 0 && size.y() > 0)) g.fail("size", "must be positive");
  // Cell counts in double until checked (size / cell may be far beyond int's range). A grid costs about
  // 200 bytes per cell (nodal fields, per-thread copies): 1e7 cells is 2 GB.
  const double nxd = std::round(size.x() / h_), nyd = std::round(size.y() / h_);
  if (!(nxd * nyd <= 1e7)) {
    std::ostringstream os;
    os << nxd << " x " << nyd << " cells (size / cell): more than 1e7, about 200 bytes each";
    g.fail(os.str());
  }
  nx_ = static_cast<int>(nxd);
  ny_ = static_cast<int>(nyd);
  if (nx_ < 1 || ny_ < 1 || std::abs(nx_ * h_ - size.x()) > 1e-9 * size.x() || std::abs(ny_ * h_ - size.y()) > 1e-9 * size.y())
    g.fail("cell", "the grid size must be a whole number of cells in each direction");
  ppc_ = b.integer("particles_per_cell", 1);
  if (ppc_ > 8) b.fail("particles_per_cell", "at most 8 per direction");
  gimp_ = b.choice("shape_functions", {"linear", "gimp"}) == "gimp";
  update_ = b.choice("update", {"musl", "usl", "usf"});
  cfl_ = b.positive("cfl");
  flip_ = b.number("flip");
  if (!(flip_ >= 0.0 && flip_ <= 1.0)) b.fail("flip", "must lie in [0, 1] (1: FLIP, 0: PIC)");
  if (cfl_ > 1) b.fail("cfl", "must lie in (0, 1]");
  gravity_ = b.boolean("gravity");
  particles_csv_ = b.boolean("particles_csv");
  grid_output_ = b.boolean("grid_output");
  Params d = b.at("damping");
  d.validate({{"local", 0.0}, {"local_until", 1e30}, {"mass", 0.0}, {"stiffness", 0.0}});
  local_until_ = d.number("local_until");
  local_damping_ = d.non_negative("local");
  if (local_damping_ >= 1) d.fail("local", "must lie in [0, 1)");
  damp_mass_ = d.non_negative("mass");
  damp_stiff_ = d.non_negative("stiffness");

  // Particles: n x n per cell, at the centres of the sub-cells that lie in a region.
  Params regions = b.at("regions");
  if (regions.size() == 0) regions.fail("at least one region is needed");
  const double hp = h_ / ppc_;
  std::vector<char> taken(static_cast<size_t>(nx_) * ny_ * ppc_ * ppc_, 0);
  for (size_t r = 0; r < regions.size(); ++r) {
    Params reg = regions.at(r);
    if (!reg.has("type")) reg.fail("type", "required key is missing");
    std::vector<Vec2> poly;
    if (reg.choice("type", {"rectangle", "polygon"}) == "rectangle") {
      reg.validate({{"type", "rectangle"}, {"origin", Json::array({0.0, 0.0})}, {"size", nullptr}});
      const Vec2 o = reg.vec2("origin"), s = reg.vec2("size");
      if (!(s.x() > 0 && s.y() > 0)) reg.fail("size", "must be positive");
      poly = {o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())};
    } else {
      reg.validate({{"type", "polygon"}, {"points", nullptr}});
      poly = reg.points("points");
      if (poly.size() < 3) reg.fail("points", "a polygon needs at least 3 points");
    }
    const size_t before = P_.size();
    for (int j = 0; j < ny_ * ppc_; ++j)
      for (int i = 0; i < nx_ * ppc_; ++i) {
        const size_t k = static_cast<size_t>(j) * nx_ * ppc_ + i;
        const Vec2 q = origin_ + Vec2((i + 0.5) * hp, (j + 0.5) * hp);
        if (taken[k] || !inside_polygon(poly, q)) continue;
        taken[k] = 1;
        P_.x.push_back(q);
        P_.X.push_back(q);
        P_.v.push_back(Vec2::Zero());
        P_.mass.push_back(rho_ * hp * hp);
        P_.volume0.push_back(hp * hp);
        P_.volume.push_back(hp * hp);
        P_.F.push_back(Mat2::Identity());
        P_.stress.push_back({0, 0, 0, 0});
        P_.strain.push_back({0, 0, 0});
        P_.plastic.push_back(0.0);
        P_.rate.push_back({0, 0, 0});
        P_.n.push_back(0.0);
        P_.p.push_back(0.0);
        P_.w.push_back(Vec2::Zero());
        P_.a.push_back(Vec2::Zero());
      }
    if (P_.size() == before) reg.fail("the region holds no particle of the grid (is it inside the grid?)");
  }

  // Initial velocity: uniform, or an axial mode v = amplitude sin(k (x - x0)) along an axis (the vibrating bar).
  const Vec2 v0 = b.vec2("initial_velocity");
  for (auto& v : P_.v) v = v0;
  Params is = b.at("initial_state");
  if (!is.has("type")) is.fail("type", "required key is missing");
  const std::string ist = is.choice("type", {"given", "axial_mode", "pulse"});
  if (ist == "pulse") {
    // v = amplitude exp(-((x - centre) / width)^2) along an axis (a wave packet for boundary tests).
    is.validate({{"type", "pulse"}, {"amplitude", nullptr}, {"centre", nullptr}, {"width", nullptr}, {"axis", "x"}});
    const int ax = is.choice("axis", {"x", "y"}) == "x" ? 0 : 1;
    const double A = is.number("amplitude"), x0 = is.number("centre"), w = is.positive("width");
    for (size_t q = 0; q < P_.size(); ++q) {
      const double r = (P_.x[q][ax] - x0) / w;
      P_.v[q] = Vec2::Zero();
      P_.v[q][ax] = A * std::exp(-r * r);
    }
  } else if (ist == "axial_mode") {
    is.validate({{"type", "axial_mode"}, {"amplitude", nullptr}, {"wavenumber", nullptr}, {"start", 0.0},
                 {"axis", "x"}});
    const int ax = is.choice("axis", {"x", "y"}) == "x" ? 0 : 1;
    const double A = is.number("amplitude"), k = is.number("wavenumber"), x0 = is.number("start");
    for (size_t p = 0; p < P_.size(); ++p) {
      P_.v[p] = Vec2::Zero();
      P_.v[p][ax] = A * std::sin(k * (P_.x[p][ax] - x0));
    }
  } else {
    is.validate({{"type", "given"}});
  }
  // Initial stress: geostatic (vertical stress from the weight above, horizontal K0 times it).
  Params st = b.at("initial_stress");
  if (!st.has("type")) st.fail("type", "required key is missing");
  if (st.choice("type", {"zero", "geostatic"}) == "geostatic") {
    st.validate({{"type", "geostatic"}, {"surface", nullptr}, {"k0", nu_ / (1 - nu_)}});
    const double top = st.number("surface"), k0 = st.non_negative("k0"), gy = ctx.gravity.y();
    k0_ = k0;
    for (size_t p = 0; p < P_.size(); ++p) {
      const double sv = rho_ * gy * (top - P_.x[p].y());  // negative (compression) below the surface
      P_.stress[p] = {k0 * sv, sv, 0.0, k0 * sv};
    }
  } else {
    st.validate({{"type", "zero"}});
    k0_ = nu_ / (1 - nu_);
  }

  // Saturated soil: the material's density is the grains'; the particle carries water (porosity n).
  if (!b.at("two_phase").json().empty()) {
    Params tp = b.at("two_phase");
    tp.validate({{"porosity", nullptr}, {"water_density", 1000.0}, {"water_bulk_modulus", 2.2e9},
                 {"hydraulic_conductivity", nullptr}, {"initial_pore_pressure", Json{{"type", "zero"}}}});
    two_phase_ = true;
    const double n0 = tp.number("porosity");
    if (!(n0 > 0 && n0 < 1)) tp.fail("porosity", "must lie in (0, 1)");
    rho_w_ = tp.positive("water_density");
    K_w_ = tp.positive("water_bulk_modulus");
    k_hyd_ = tp.positive("hydraulic_conductivity");
    if (plastic_ || update_ != "musl") tp.fail("two-phase bodies are linear elastic with the MUSL update in this version");
    Params ip = tp.at("initial_pore_pressure");
    if (!ip.has("type")) ip.fail("type", "required key is missing");
    double level = 0;
    const bool hydro = ip.choice("type", {"zero", "hydrostatic"}) == "hydrostatic";
    if (hydro) {
      ip.validate({{"type", "hydrostatic"}, {"level", nullptr}});
      level = ip.number("level");
    } else {
      ip.validate({{"type", "zero"}});
    }
    for (size_t q = 0; q < P_.size(); ++q) {
      P_.n[q] = n0;
      P_.mass[q] = ((1 - n0) * rho_ + n0 * rho_w_) * P_.volume0[q];  // saturated mass (probes, energy)
      // Tension positive: a hydrostatic pressure is negative below the level.
      if (hydro) P_.p[q] = std::min(0.0, rho_w_ * ctx.gravity.y() * (level - P_.x[q].y()));
    }
  }

  // Loads on particles: the total force split equally over the particles whose reference position the
  // selection picks, times a function of time.
  Params loads = b.at("loads");
  for (size_t i = 0; i < loads.size(); ++i) {
    Params l = loads.at(i);
    l.validate({{"type", "particle_force"}, {"select", nullptr}, {"value", nullptr}, {"function", Json{{"type", "constant"}}}});
    l.choice("type", {"particle_force"});
    ParticleLoad pl;
    pl.particles = select_nodes(l.at("select"), P_.X);
    pl.force = l.vec2("value") / static_cast<double>(pl.particles.size());
    pl.fn = make_time_function(l.at("function"), ctx.base_dir);
    loads_.push_back(std::move(pl));
  }

  // Grid boundary conditions: fixed components of the selected grid nodes.
  std::vector<Vec2> nodes;
  for (int j = 0; j <= ny_; ++j)
    for (int i = 0; i <= nx_; ++i) nodes.push_back(origin_ + Vec2(i * h_, j * h_));
  Params bcs = b.at("boundary_conditions");
  for (size_t i = 0; i < bcs.size(); ++i) {
    Params bc = bcs.at(i);
    if (!bc.json().is_object() || !bc.has("type")) bc.fail("type", "required key is missing");
    const std::string type = bc.choice("type", {"fixed", "prescribed_velocity", "prescribed_acceleration"});
    if (type == "fixed") {
      bc.validate({{"type", "fixed"}, {"select", nullptr}, {"components", "xy"}});
      const std::string comps = bc.choice("components", {"x", "y", "xy"});
      for (Index n : select_nodes(bc.at("select"), nodes)) {
        if (comps != "y") fixed_.push_back({n, 0});
        if (comps != "x") fixed_.push_back({n, 1});
      }
      continue;
    }
    // The selected nodes move with value * f(t) (velocity) or value * int f (acceleration); both components
    // whose value is non-zero are prescribed, and "fixed" other components stay fixed.
    bc.validate({{"type", type}, {"select", nullptr}, {"value", nullptr}, {"function", nullptr}});
    if (two_phase_) bc.fail("type", "prescribed motion of two-phase bodies is not available in this version");
    const Vec2 value = bc.vec2("value");
    std::shared_ptr<TimeFunction> fn = make_time_function(bc.at("function"), ctx.base_dir);
    for (Index n : select_nodes(bc.at("select"), nodes))
      for (int c = 0; c < 2; ++c)
        if (value[c] != 0.0) moving_.push_back({n, c, value[c], fn, type == "prescribed_acceleration"});
  }
  implicit_ = b.choice("time_integration", {"explicit", "implicit"}) == "implicit";
  if (!implicit_) {
    // The explicit substep is cfl h / c (solve_iteration); a stiff, light or nearly water-filled body could
    // ask for billions of them and the run would look hung.
    const double n0 = two_phase_ && !P_.n.empty() ? P_.n[0] : 0.0;
    const double rho_sat = two_phase_ ? (1 - n0) * rho_ + n0 * rho_w_ : rho_;
    const double c = std::sqrt((lambda_ + 2 * mu_ + (two_phase_ ? K_w_ / n0 : 0.0)) / rho_sat);
    const double substeps = ctx.analysis.end_time * c / (cfl_ * h_);
    // particle and grid-node updates (the grid is cleared and solved every substep); ~0.1-1 us each
    const double work = substeps * (static_cast<double>(P_.size()) + (nx_ + 1.0) * (ny_ + 1.0));
    if (!(substeps <= 1e8) || !(work <= 1e11)) {
      std::ostringstream os;
      os << "the explicit scheme's stable step cfl h / c (wave speed c = " << c << " m/s, cell " << h_
         << " m) needs " << substeps << " substeps over the run (" << work
         << " particle and grid-node updates; the limits are 1e8 and 1e11): check the density, stiffness"
         << (two_phase_ ? ", porosity" : "") << " and cell size";
      b.fail("material", os.str());
    }
  }
  if (implicit_) {
    if (plastic_ || two_phase_ || local_damping_ > 0 || damp_stiff_ > 0 || damp_mass_ > 0)
      b.fail("time_integration", "implicit MPM bodies are linear elastic, single phase and undamped in this version");
    Params ip(ctx.analysis.integrator, ctx.case_file.string(), "/analysis/integrator");
    const std::string it = ip.string("type");
    if (it == "central_difference") b.fail("time_integration", "an implicit MPM body needs newmark or generalized_alpha");
    integrator_ = it == "generalized_alpha" ? make_generalized_alpha(ip.number("rho_inf"))
                                            : make_newmark(ip.number("beta"), ip.number("gamma"));
    solver_ = make_linear_solver("cholmod");
  }
  Params ab = b.at("absorbing_boundaries");
  for (size_t i = 0; i < ab.size(); ++i) {
    Params a = ab.at(i);
    a.validate({{"select", nullptr}, {"normal", nullptr}, {"free_field", false}, {"start", 0.0}});
    if (!a.boolean("free_field") && a.non_negative("start") > 0) a.fail("start", "is for free-field boundaries");
    if (two_phase_) a.fail("select", "absorbing boundaries of two-phase bodies are not available in this version");
    Vec2 nrm = a.vec2("normal");
    if (!(nrm.norm() > 0)) a.fail("normal", "must be a non-zero vector");
    nrm.normalize();
    const auto sel = select_nodes(a.at("select"), nodes);
    if (a.boolean("free_field")) {
      if (std::abs(nrm.y()) > 1e-12) a.fail("normal", "a free-field boundary is lateral: its outward normal is [1, 0] or [-1, 0]");
      FreeField ff;
      ff.normal = nrm;
      ff.start = a.non_negative("start");
      std::vector<Index> col(sel.begin(), sel.end());
      std::sort(col.begin(), col.end(), [&](Index p, Index q) { return nodes[p].y() < nodes[q].y(); });
      for (size_t k = 1; k < col.size(); ++k)
        if (std::abs(nodes[col[k]].x() - nodes[col[0]].x()) > 1e-6 * h_ ||
            std::abs(nodes[col[k]].y() - nodes[col[k - 1]].y() - h_) > 1e-6 * h_)
          a.fail("select", "a free-field boundary is one vertical line of consecutive grid nodes");
      // The column's soil: up to the top of the particles next to the boundary (their domains' top).
      const double xb = nodes[col[0]].x();
      double top = -std::numeric_limits<double>::infinity();
      for (size_t q = 0; q < P_.size(); ++q)
        if (std::abs(P_.x[q].x() - xb) < h_) top = std::max(top, P_.x[q].y() + 0.5 * h_ / ppc_);
      if (!(top > nodes[col[0]].y() + 0.5 * h_)) a.fail("select", "no material next to the free-field boundary");
      const double gy = gravity_ ? ctx.gravity.y() : 0.0;
      for (size_t k = 0; k < col.size(); ++k) {
        const double y = nodes[col[k]].y();
        if (y > top + 1e-9 * h_) break;
        ff.nodes.push_back(col[k]);
        ff.sv.push_back(rho_ * gy * (top - y));
        if (k + 1 < col.size() && nodes[col[k + 1]].y() <= top + 1e-9 * h_) ff.le.push_back(h_);
        else if (top - y > 1e-9 * h_) {  // a partial last element up to the top
          ff.le.push_back(top - y);
          ff.nodes.push_back(col[k + 1 < col.size() ? k + 1 : k]);
          ff.sv.push_back(0.0);
          if (k + 1 >= col.size()) a.fail("select", "the free-field boundary must reach the top of the material");
          break;
        }
      }
      const size_t m = ff.nodes.size();
      if (m < 2) a.fail("select", "a free-field column needs at least two nodes in the material");
      ff.mass.assign(m, 0.0);
      ff.length.assign(m, 0.0);
      for (size_t k = 0; k + 1 < m; ++k) {
        ff.mass[k] += 0.5 * rho_ * ff.le[k];
        ff.mass[k + 1] += 0.5 * rho_ * ff.le[k];
        ff.length[k] += 0.5 * ff.le[k];
        ff.length[k + 1] += 0.5 * ff.le[k];
      }
      ff.u.assign(m, Vec2::Zero());
      ff.v.assign(m, Vec2::Zero());
      ff.reaction.assign(m, 0.0);
      for (const auto& mv : moving_)
        if (mv.node == ff.nodes[0]) ff.base[mv.comp] = &mv;
      for (const auto& [node, comp] : fixed_)
        if (node == ff.nodes[0]) ff.base_fixed[comp] = true;
      for (const auto& mv : moving_)
        for (size_t k = 1; k < m; ++k)
          if (mv.node == ff.nodes[k]) a.fail("select", "a free-field node above the base must not have a prescribed motion");
      free_fields_.push_back(std::move(ff));
      continue;
    }
    const std::set<Index> in(sel.begin(), sel.end());
    const Vec2 tangent(-nrm.y(), nrm.x());
    for (Index n : sel) {
      double length = 0;
      for (double s : {-1.0, 1.0}) {
        const Vec2 q = nodes[n] + s * h_ * tangent;  // the neighbour along the boundary, if on the grid
        const long i = std::lround((q.x() - origin_.x()) / h_), j = std::lround((q.y() - origin_.y()) / h_);
        if (i < 0 || j < 0 || i > nx_ || j > ny_) continue;
        if ((nodes[j * (nx_ + 1) + i] - q).norm() < 1e-6 * h_ && in.count(static_cast<Index>(j * (nx_ + 1) + i)))
          length += 0.5 * h_;
      }
      if (length == 0) length = h_;  // a single node: one cell's length
      dashpots_.push_back({n, nrm, length});
    }
  }
  if (implicit_ && (!moving_.empty() || !dashpots_.empty()))
    b.fail("time_integration", "implicit MPM bodies take fixed nodes only (no prescribed motion or absorbing boundaries) in this version");
  const size_t nn = nodes.size();
  gm_.assign(nn, 0.0);
  gp_.assign(nn, Vec2::Zero());
  gf_.assign(nn, Vec2::Zero());
  gv_.assign(nn, Vec2::Zero());
}

// ------------------------------------------------------------------------------------------ kernels

void MpmModel::support(const Vec2& x, Support& s) const {
  // Per direction: the nodes within reach and the 1D function and its derivative.
  std::array<std::array<double, 3>, 2> w{}, dw{};
  std::array<int, 2> first{}, count{};
  for (int c = 0; c < 2; ++c) {
    const double xi = (x[c] - origin_[c]) / h_;  // in cells
    const int n_cells = c == 0 ? nx_ : ny_;
    if (!gimp_) {
      int i = static_cast<int>(std::floor(xi));
      i = std::clamp(i, 0, n_cells - 1);
      const double r = xi - i;
      first[c] = i;
      count[c] = 2;
      w[c] = {1.0 - r, r, 0.0};
      dw[c] = {-1.0 / h_, 1.0 / h_, 0.0};
    } else {
      const double lp = 0.5 / ppc_;  // particle half-width in cells
      const int i0 = std::max(0, static_cast<int>(std::floor(xi - lp)));
      const int i1 = std::min(n_cells, static_cast<int>(std::floor(xi + lp)) + 1);
      first[c] = i0;
      count[c] = std::min(3, i1 - i0 + 1);
      for (int k = 0; k < count[c]; ++k) {
        const double r = xi - (i0 + k), a = std::abs(r), sg = r < 0 ? -1.0 : 1.0;
        double f = 0, df = 0;
        if (a < lp) {
          f = 1.0 - (r * r + lp * lp) / (2.0 * lp);
          df = -r / lp;
        } else if (a < 1.0 - lp) {
          f = 1.0 - a;
          df = -sg;
        } else if (a < 1.0 + lp) {
          f = (1.0 + lp - a) * (1.0 + lp - a) / (4.0 * lp);
          df = -sg * (1.0 + lp - a) / (2.0 * lp);
        }
        w[c][k] = f;
        dw[c][k] = df / h_;
      }
    }
  }
  s.n = 0;
  for (int b = 0; b < count[1]; ++b)
    for (int a = 0; a < count[0]; ++a) {
      const double N = w[0][a] * w[1][b];
      const Vec2 dN(dw[0][a] * w[1][b], w[0][a] * dw[1][b]);
      if (N == 0.0 && dN.squaredNorm() == 0.0) continue;
      s.node[s.n] = (first[1] + b) * (nx_ + 1) + first[0] + a;
      s.N[s.n] = N;
      s.dN[s.n] = dN;
      ++s.n;
    }
}

double MpmModel::return_mapping(std::array<double, 4>& s) const {
  // Principal stresses (tension positive): the in-plane pair from the 2 x 2 block, and sigma_zz.
  const double c = 0.5 * (s[0] + s[1]), r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
  const double theta = 0.5 * std::atan2(2 * s[2], s[0] - s[1]);  // direction of the larger in-plane value
  std::array<double, 3> sp = {c + r, c - r, s[3]};               // in-plane max, in-plane min, zz
  std::array<int, 3> order = {0, 1, 2};                          // indices of s1 >= s2 >= s3
  std::sort(order.begin(), order.end(), [&](int a, int b) { return sp[a] > sp[b]; });
  Vec3 sig(sp[order[0]], sp[order[1]], sp[order[2]]);
  const double k = 2 * cohesion_ * cos_phi_;
  auto f_main = [&](const Vec3& x) { return (x[0] - x[2]) + (x[0] + x[2]) * sin_phi_ - k; };
  const double f0 = f_main(sig);
  const bool yields = f0 > 1e-12 * (std::abs(sig[0]) + std::abs(sig[2]) + k);
  if (!yields && sig[0] <= tension_cutoff_) return 0.0;
  // Yield normal m and flow direction n of a plane through (i, j) (i the largest, j the smallest principal).
  auto plane = [&](int i, int j, Vec3& m, Vec3& n) {
    m.setZero();
    n.setZero();
    m[i] = 1 + sin_phi_;
    m[j] = -(1 - sin_phi_);
    n[i] = 1 + sin_psi_;
    n[j] = -(1 - sin_psi_);
  };
  auto D = [&](const Vec3& n) -> Vec3 { return Vec3::Constant(lambda_ * n.sum()) + 2 * mu_ * n; };
  const double apex = sin_phi_ > 0 ? cohesion_ * cos_phi_ / sin_phi_ : 0.0;  // mean stress at the apex
  Vec3 m1, n1;
  plane(0, 2, m1, n1);
  const Vec3 Dn1 = D(n1);
  double dgamma = yields ? f0 / m1.dot(Dn1) : 0.0;
  Vec3 out = sig - dgamma * Dn1;
  if (yields && !(out[0] >= out[1] && out[1] >= out[2])) {
    // The return left the sextant: two planes are active (an edge), s1 = s2 or s2 = s3 at the end.
    Vec3 m2, n2;
    if (out[1] > out[0]) plane(1, 2, m2, n2);  // edge s1 = s2: planes (1, 3) and (2, 3)
    else plane(0, 1, m2, n2);                  // edge s2 = s3: planes (1, 3) and (1, 2)
    const Vec3 Dn2 = D(n2);
    const double f2 = m2.dot(sig) - k;
    const double a11 = m1.dot(Dn1), a12 = m1.dot(Dn2), a21 = m2.dot(Dn1), a22 = m2.dot(Dn2);
    const double det = a11 * a22 - a12 * a21;
    const double g1 = (a22 * f0 - a12 * f2) / det, g2 = (a11 * f2 - a21 * f0) / det;
    out = sig - g1 * Dn1 - g2 * Dn2;
    dgamma = g1 + g2;
    if (!(g1 >= 0 && g2 >= 0)) dgamma = -1;  // no admissible edge return: the apex below
  }
  // Beyond the apex (tension past c cot(phi), or an edge return with a negative multiplier): the apex.
  if (yields && (out.sum() / 3 > apex || out[0] > apex + 1e-9 * (std::abs(apex) + 1) || !(dgamma >= 0))) {
    out = Vec3::Constant(apex);
    dgamma = std::max(dgamma, 0.0) + (sig - out).norm() / (2 * mu_);
  }
  // Tension cut-off (a Rankine cap below the apex): no principal stress above it.
  for (int a = 0; a < 3; ++a)
    if (out[a] > tension_cutoff_) {
      dgamma += (out[a] - tension_cutoff_) / (2 * mu_);
      out[a] = tension_cutoff_;
    }
  // Back to (xx, yy, xy, zz) with the trial's principal directions.
  std::array<double, 3> back{};
  for (int a = 0; a < 3; ++a) back[order[a]] = out[a];
  const double cc = 0.5 * (back[0] + back[1]), rr = 0.5 * (back[0] - back[1]);
  s[0] = cc + rr * std::cos(2 * theta);
  s[1] = cc - rr * std::cos(2 * theta);
  s[2] = rr * std::sin(2 * theta);
  s[3] = back[2];
  return dgamma;
}

void MpmModel::stress_update(double dt, const std::vector<Vec2>& vgrid) {
  const Index np = static_cast<Index>(P_.size());
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index p = 0; p < np; ++p) {
    const Support& s = sup_[p];
    Mat2 L = Mat2::Zero();
    for (int k = 0; k < s.n; ++k) L += vgrid[s.node[k]] * s.dN[k].transpose();
    P_.F[p] = (Mat2::Identity() + dt * L) * P_.F[p];
    const Mat2& F = P_.F[p];
    P_.volume[p] = (F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0)) * P_.volume0[p];
    const double dxx = dt * L(0, 0), dyy = dt * L(1, 1), dxy = 0.5 * dt * (L(0, 1) + L(1, 0));
    P_.rate[p] = {L(0, 0), L(1, 1), 0.5 * (L(0, 1) + L(1, 0))};  // for the stiffness-proportional damping
    const double tr = dxx + dyy;
    auto& sg = P_.stress[p];
    // Jaumann rate: the stress turns with the spin W = (L - L^T)/2, w = W_xy dt (sigma += W sigma - sigma W).
    const double w = 0.5 * dt * (L(0, 1) - L(1, 0));
    const double rxx = 2 * w * sg[2], rxy = w * (sg[1] - sg[0]);
    sg[0] += lambda_ * tr + 2 * mu_ * dxx + rxx;
    sg[1] += lambda_ * tr + 2 * mu_ * dyy - rxx;
    sg[2] += 2 * mu_ * dxy + rxy;
    sg[3] += lambda_ * tr;
    if (plastic_) P_.plastic[p] += return_mapping(sg);
    auto& e = P_.strain[p];
    e[0] += dxx;
    e[1] += dyy;
    e[2] += dxy;
  }
}

void MpmModel::scatter(bool momentum, bool force) {
  // Particles to grid, in parallel: each thread accumulates its share of the particles into its own copy of
  // the grid arrays, then the copies are summed node by node (a particle's nodes are shared with its
  // neighbours', so a direct parallel scatter would race).
  const Index np = static_cast<Index>(P_.size());
  const Index nn = static_cast<Index>(gm_.size());
  const Vec2 g = gravity_ ? ctx_.gravity : Vec2::Zero();
  int nt = 1;
#ifdef _OPENMP
  nt = np >= 20000 ? omp_get_max_threads() : 1;
#endif
  if (static_cast<int>(tm_.size()) != nt) {
    tm_.assign(nt, {});
    tp_.assign(nt, {});
    tf_.assign(nt, {});
  }
#pragma omp parallel num_threads(nt)
  {
    int tid = 0;
#ifdef _OPENMP
    tid = omp_get_thread_num();
#endif
    auto& m = tm_[tid];
    auto& mv = tp_[tid];
    auto& f = tf_[tid];
    if (momentum) {
      m.assign(nn, 0.0);
      mv.assign(nn, Vec2::Zero());
    }
    if (force) f.assign(nn, Vec2::Zero());
#pragma omp for schedule(static)
    for (Index p = 0; p < np; ++p) {
      const Support& sp = sup_[p];
      const double mp = P_.mass[p];
      const Vec2 mvp = mp * P_.v[p];
      std::array<double, 4> sg = P_.stress[p];
      if (damp_stiff_ > 0) {  // Rayleigh stiffness-proportional damping: the viscous stress beta C : D
        const auto& r = P_.rate[p];
        const double tr = r[0] + r[1];
        sg[0] += damp_stiff_ * (lambda_ * tr + 2 * mu_ * r[0]);
        sg[1] += damp_stiff_ * (lambda_ * tr + 2 * mu_ * r[1]);
        sg[2] += damp_stiff_ * 2 * mu_ * r[2];
      }
      const double V = P_.volume[p];
      for (int k = 0; k < sp.n; ++k) {
        const Index I = sp.node[k];
        if (momentum) {
          m[I] += sp.N[k] * mp;
          mv[I] += sp.N[k] * mvp;
        }
        if (force) {
          const Vec2& d = sp.dN[k];
          f[I] += sp.N[k] * mp * g - V * Vec2(sg[0] * d.x() + sg[2] * d.y(), sg[2] * d.x() + sg[1] * d.y());
        }
      }
    }
#pragma omp for schedule(static)
    for (Index I = 0; I < nn; ++I) {
      if (momentum) {
        double a = 0;
        Vec2 b = Vec2::Zero();
        for (int t = 0; t < nt; ++t) {
          a += tm_[t][I];
          b += tp_[t][I];
        }
        gm_[I] = a;
        gp_[I] = b;
      }
      if (force) {
        Vec2 c = Vec2::Zero();
        for (int t = 0; t < nt; ++t) c += tf_[t][I];
        gf_[I] = c;
      }
    }
  }
}

void MpmModel::locate_particles() {
  const Index np = static_cast<Index>(P_.size());
  sup_.resize(np);
  Index outside = -1;
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index p = 0; p < np; ++p) {
    const Vec2& x = P_.x[p];
    if (!(x.x() >= origin_.x() && x.y() >= origin_.y() && x.x() <= origin_.x() + nx_ * h_ &&
          x.y() <= origin_.y() + ny_ * h_)) {
#pragma omp critical(lagfsi_mpm_outside)
      outside = p;
      continue;
    }
    support(x, sup_[p]);
  }
  if (outside >= 0)
    throw SolverError("body '" + name_ + "': particle " + std::to_string(outside) + " left the grid at t = " +
                      std::to_string(t_));
}

void MpmModel::substep(double dt) {
  const Index np = static_cast<Index>(P_.size());
  const size_t nn = gm_.size();
  locate_particles();
  const Vec2 g = gravity_ ? ctx_.gravity : Vec2::Zero();
  if (update_ == "usf") {
    scatter(true, false);
    apply_fixed(gp_);
    for (size_t i = 0; i < nn; ++i) gv_[i] = gm_[i] > 0 ? Vec2(gp_[i] / gm_[i]) : Vec2::Zero();
    stress_update(dt, gv_);
    scatter(false, true);
  } else {
    scatter(true, true);
    apply_fixed(gp_);
  }
  add_loads(gf_, t_);
  // Grid update; local (Cundall) damping opposes the node's motion with a share of its unbalanced force;
  // Rayleigh mass-proportional damping is the force -alpha m_I v_I.
  for (size_t i = 0; i < nn; ++i) {
    if (!(gm_[i] > 0)) continue;
    if (damp_mass_ > 0) gf_[i] -= damp_mass_ * gp_[i];
  }
  add_free_field_tractions();
  for (size_t i = 0; i < nn; ++i) {
    if (!(gm_[i] > 0)) continue;
    if (local_damping_ > 0 && t_ < local_until_) {
      const Vec2 v = gp_[i] / gm_[i];
      for (int c = 0; c < 2; ++c)
        if (v[c] != 0.0) gf_[i][c] -= local_damping_ * std::abs(gf_[i][c]) * (v[c] > 0 ? 1.0 : -1.0);
    }
  }
  apply_fixed(gf_);
  add_dashpot_forces(dt);
  step_free_fields(dt);
  apply_fixed(gf_);
  for (size_t i = 0; i < nn; ++i) {
    if (!(gm_[i] > 0)) continue;
    gp_[i] += dt * gf_[i];
    gv_[i] = gp_[i] / gm_[i];
  }
  apply_fixed(gv_);
  // Prescribed motion: the node's velocity at the end of the sub-step; its force is what that takes.
  for (const auto& m : moving_) {
    if (!(gm_[m.node] > 0)) continue;
    const double v1 = m.velocity(t_ + dt);
    gf_[m.node][m.comp] += gm_[m.node] * (v1 - gv_[m.node][m.comp]) / dt;
    gv_[m.node][m.comp] = v1;
    gp_[m.node][m.comp] = gm_[m.node] * v1;
  }
  // Grid to particles: FLIP velocity, positions with the grid velocity.
  double gw = 0;
#pragma omp parallel for schedule(static) if (np >= 20000) reduction(+ : gw)
  for (Index p = 0; p < np; ++p) {
    const Support& s = sup_[p];
    Vec2 a = Vec2::Zero(), v = Vec2::Zero();
    for (int k = 0; k < s.n; ++k) {
      const Index I = s.node[k];
      if (!(gm_[I] > 0)) continue;
      a += s.N[k] * gf_[I] / gm_[I];
      v += s.N[k] * gv_[I];
    }
    P_.v[p] = flip_ * (P_.v[p] + dt * a) + (1.0 - flip_) * v;
    P_.a[p] = a;
    const Vec2 dx = dt * v;
    P_.x[p] += dx;
    gw += P_.mass[p] * g.dot(dx);
  }
  gravity_work_ += gw;
  if (update_ == "musl") {
    scatter(true, false);
    for (size_t i = 0; i < nn; ++i) gv_[i] = gm_[i] > 0 ? Vec2(gp_[i] / gm_[i]) : Vec2::Zero();
    apply_fixed(gv_);
    for (const auto& m : moving_) gv_[m.node][m.comp] = m.velocity(t_ + dt);
  }
  if (update_ != "usf") stress_update(dt, gv_);
  for (Index p = 0; p < np; ++p)
    if (!(P_.volume[p] > 0) || !std::isfinite(P_.stress[p][1]))
      throw SolverError("body '" + name_ + "': particle " + std::to_string(p) + " inverted or non-finite at t = " +
                        std::to_string(t_));
}

// ------------------------------------------------------------------------------------------ lifecycle

void MpmModel::add_free_field_tractions() {
  for (auto& ff : free_fields_) {
    const size_t m = ff.nodes.size();
    if (!ff.active(t_)) continue;
    for (size_t k = 0; k < m; ++k) {
      const Index n = ff.nodes[k];
      if (!(gm_[n] > 0)) continue;
      // Column stress at the node: the average of its elements' (the static part at the node).
      Vec2 e = Vec2::Zero();
      int ne = 0;
      for (size_t el : {k - 1, k})
        if (el < m - 1) {
          e += ff.strain(el, damp_stiff_);
          ++ne;
        }
      e /= ne;
      // e = (gamma_xy, eps_yy) with the body's stiffness-proportional damping: sigma_xx = K0 sigma_v +
      // lambda eps_yy, sigma_xy = mu gamma_xy.
      const double sxx = (ff.start > 0 ? 0.0 : k0_ * ff.sv[k]) + lambda_ * e.y();
      const double sxy = mu_ * e.x();
      gf_[n] += ff.length[k] * Vec2(sxx * ff.normal.x(), sxy * ff.normal.x()) + Vec2(ff.reaction[k], 0.0);
    }
  }
}

void MpmModel::add_dashpot_forces(double dt) {
  // A dashpot force -C (v - v_ref), C = rho L (c_p n n^T + c_s (I - n n^T)), taken at the end-of-step
  // velocity: (m I + dt C) v_new = p + dt f + dt C v_ref. Implicit in the node's own velocity, it is stable for
  // any nodal mass (an explicit dashpot on a node with little mass, at the edge of the material, is not).
  const double cp = std::sqrt((lambda_ + 2 * mu_) / rho_), cs = std::sqrt(mu_ / rho_);
  auto apply = [&](Index n, const Vec2& normal, double length, const Vec2& v_ref) {
    if (!(gm_[n] > 0)) return;
    const Mat2 nn = normal * normal.transpose();
    const Mat2 C = rho_ * length * (cp * nn + cs * (Mat2::Identity() - nn));
    const Mat2 A = gm_[n] * Mat2::Identity() + dt * C;
    const Vec2 v_new = A.inverse() * (gp_[n] + dt * gf_[n] + dt * C * v_ref);
    gf_[n] -= C * (v_new - v_ref);
  };
  for (const auto& d : dashpots_) apply(d.node, d.normal, d.length, Vec2::Zero());
  for (auto& ff : free_fields_)
    for (size_t k = 0; k < ff.nodes.size(); ++k) {
      const Index n = ff.nodes[k];
      if (ff.active(t_)) {
        apply(n, ff.normal, ff.length[k], ff.v[k]);
      } else if (gm_[n] > 0) {  // a roller: its reaction holds the node's horizontal momentum
        ff.reaction[k] = -(gp_[n].x() / dt + gf_[n].x());
        gf_[n].x() += ff.reaction[k];
      }
    }
}

void MpmModel::step_free_fields(double dt) {
  for (auto& ff : free_fields_) {
    const size_t m = ff.nodes.size();
    std::vector<Vec2> f(m, Vec2::Zero());
    for (size_t k = 0; k + 1 < m; ++k) {
      // Element stress: shear mu gamma, axial (lambda + 2 mu) eps (1D constrained), with the body's
      // stiffness-proportional damping; per unit width.
      const Vec2 e = ff.strain(k, damp_stiff_);
      const Vec2 s(mu_ * e.x(), (lambda_ + 2 * mu_) * e.y());
      f[k] += s;
      f[k + 1] -= s;
    }
    for (size_t k = 0; k < m; ++k) {
      if (damp_mass_ > 0) f[k] -= damp_mass_ * ff.mass[k] * ff.v[k];
      ff.v[k] += dt * f[k] / ff.mass[k];
    }
    for (int c = 0; c < 2; ++c) {  // the base moves with the grid's base
      if (ff.base[c]) ff.v[0][c] = ff.base[c]->velocity(t_ + dt);
      else if (ff.base_fixed[c]) ff.v[0][c] = 0.0;
    }
    for (size_t k = 0; k < m; ++k) ff.u[k] += dt * ff.v[k];
  }
}

void MpmModel::initialize() { t_ = 0; }

void MpmModel::substep_two_phase(double dt) {
  // Seed 000 eqs. 3.52-3.84 with the digest's sign fixes: p is tension positive, sigma = sigma' + p I.
  //   water:  m_w a_w = F_w,grav - F_w,int - Q (w - v),   F_w,int = sum V_p p_p grad N,  q = sum n m_w g / k N
  //   solid:  m_s a_s = -mbar_w a_w + F_grav + F_trac - F_int,   F_int = sum V_p sigma_p grad N (total stress)
  //   then particle velocities (FLIP), MUSL re-map of both velocities, positions with the solid's, and
  //   p += dt (K_w / n) [(1 - n) div v + n div w], n from the volume change (incompressible grains).
  const Index np = static_cast<Index>(P_.size());
  const size_t nn = gm_.size();
  locate_particles();
  auto zero = [nn](std::vector<Vec2>& a) { a.assign(nn, Vec2::Zero()); };
  gms_.assign(nn, 0.0);
  gmw_.assign(nn, 0.0);
  gmwn_.assign(nn, 0.0);
  gq_.assign(nn, 0.0);
  zero(gps_), zero(gpw_), zero(gfs_), zero(gfw_);
  const Vec2 g = gravity_ ? ctx_.gravity : Vec2::Zero();
  // The drag converts the hydraulic conductivity k (m/s) with the unit weight of water rho_w |g|; without
  // gravity (a weightless layer) |g| = 9.81 m/s^2 is used.
  const double g_drag = ctx_.gravity.norm() > 0 ? ctx_.gravity.norm() : 9.81;
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    const double n = P_.n[q], V = P_.volume[q], V0 = P_.volume0[q];
    const double ms = rho_ * V0, mw = rho_w_ * V0;  // the particle's grain and water mass scales
    const auto& sg = P_.stress[q];
    const double pw = P_.p[q];
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      const double N = sp.N[k];
      const Vec2& d = sp.dN[k];
      gms_[I] += N * (1 - n) * ms;
      gmw_[I] += N * mw;
      gmwn_[I] += N * n * mw;
      gq_[I] += N * n * mw * g_drag / k_hyd_;
      gps_[I] += N * (1 - n) * ms * P_.v[q];
      gpw_[I] += N * n * mw * P_.w[q];
      const double sxx = sg[0] + pw, syy = sg[1] + pw;  // total stress
      gfs_[I] += N * ((1 - n) * ms + n * mw) * g - V * Vec2(sxx * d.x() + sg[2] * d.y(), sg[2] * d.x() + syy * d.y());
      gfw_[I] += N * mw * g - V * pw * d;
    }
  }
  // Particle loads act on the mixture.
  add_loads(gfs_, t_);
  gvs_.assign(nn, Vec2::Zero());
  gvw_.assign(nn, Vec2::Zero());
  gas_.assign(nn, Vec2::Zero());
  gaw_.assign(nn, Vec2::Zero());
  for (size_t I = 0; I < nn; ++I) {
    if (!(gms_[I] > 0)) continue;
    gvs_[I] = gps_[I] / gms_[I];
    gvw_[I] = gpw_[I] / gmwn_[I];
  }
  apply_fixed(gvs_);
  apply_fixed(gvw_);
  for (size_t I = 0; I < nn; ++I) {
    if (!(gms_[I] > 0)) continue;
    // The drag is stiff for low conductivity: treated implicitly in w (semi-implicit: the w of the drag at the
    // end of the step), m_w a_w = F - Q (w + dt a_w - v).
    const Vec2 F = gfw_[I] - gq_[I] * (gvw_[I] - gvs_[I]);
    gaw_[I] = F / (gmw_[I] + dt * gq_[I]);
    gas_[I] = (gfs_[I] - gmwn_[I] * gaw_[I]) / gms_[I];
  }
  apply_fixed(gas_);
  apply_fixed(gaw_);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    Vec2 as = Vec2::Zero(), aw = Vec2::Zero();
    for (int k = 0; k < sp.n; ++k) {
      as += sp.N[k] * gas_[sp.node[k]];
      aw += sp.N[k] * gaw_[sp.node[k]];
    }
    P_.v[q] += dt * as;
    P_.w[q] += dt * aw;
  }
  // MUSL re-map of both velocities from the updated particles.
  zero(gps_), zero(gpw_);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    const double n = P_.n[q], ms = rho_ * P_.volume0[q], mw = rho_w_ * P_.volume0[q];
    for (int k = 0; k < sp.n; ++k) {
      gps_[sp.node[k]] += sp.N[k] * (1 - n) * ms * P_.v[q];
      gpw_[sp.node[k]] += sp.N[k] * n * mw * P_.w[q];
    }
  }
  for (size_t I = 0; I < nn; ++I) {
    gvs_[I] = gms_[I] > 0 ? Vec2(gps_[I] / gms_[I]) : Vec2::Zero();
    gvw_[I] = gmwn_[I] > 0 ? Vec2(gpw_[I] / gmwn_[I]) : Vec2::Zero();
  }
  apply_fixed(gvs_);
  apply_fixed(gvw_);
  double gw = 0;
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    Vec2 v = Vec2::Zero();
    Mat2 Ls = Mat2::Zero();
    double divw = 0;
    for (int k = 0; k < sp.n; ++k) {
      v += sp.N[k] * gvs_[sp.node[k]];
      Ls += gvs_[sp.node[k]] * sp.dN[k].transpose();
      divw += gvw_[sp.node[k]].dot(sp.dN[k]);
    }
    const Vec2 dx = dt * v;
    P_.x[q] += dx;
    gw += P_.mass[q] * g.dot(dx);
    // Effective stress (linear elastic), pore pressure, porosity, volume.
    const double n = P_.n[q];
    P_.p[q] += dt * (K_w_ / n) * ((1 - n) * (Ls(0, 0) + Ls(1, 1)) + n * divw);
    const double V_old = P_.volume[q];
    elastic_increment(q, dt * Ls);
    P_.n[q] = 1 - (1 - n) * V_old / P_.volume[q];
    if (!(P_.volume[q] > 0) || !std::isfinite(P_.p[q]) || !(P_.n[q] > 0 && P_.n[q] < 1))
      throw SolverError("body '" + name_ + "': particle " + std::to_string(q) + " inverted or non-finite at t = " +
                        std::to_string(t_));
  }
  gravity_work_ += gw;
}

void MpmModel::step_implicit(double dt) {
  // Grid state at t_n from the particles: positions of the nodes, velocities and accelerations mapped with the
  // particles' masses. The step's unknowns are the new node positions x_{n+1} (2 per node, as for the solid);
  // the time integrator gives a(x) and v(x), and the residual
  //   r(x) = M a(x) + f_int(x) - f_ext,   f_int = sum_p V_p B_p^T (sigma_p + D : sym(grad (x - x_n))),
  // is linear in x (small strain), so one solve with H = c_m M + c_k K is exact. Empty nodes are held.
  const Index np = static_cast<Index>(P_.size());
  const Index nn = static_cast<Index>(gm_.size());
  locate_particles();
  Vec mass = Vec::Zero(nn), mv = Vec::Zero(2 * nn), ma = Vec::Zero(2 * nn), fext = Vec::Zero(2 * nn), fint0 = Vec::Zero(2 * nn);
  const Vec2 g = gravity_ ? ctx_.gravity : Vec2::Zero();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(np) * 18 * 18);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    const auto& sg = P_.stress[q];
    const double V = P_.volume[q], mq = P_.mass[q];
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      const double N = sp.N[k];
      const Vec2& d = sp.dN[k];
      mass[I] += N * mq;
      mv.segment<2>(2 * I) += N * mq * P_.v[q];
      ma.segment<2>(2 * I) += N * mq * P_.a[q];
      fext.segment<2>(2 * I) += N * mq * g;
      fint0.segment<2>(2 * I) += V * Vec2(sg[0] * d.x() + sg[2] * d.y(), sg[2] * d.x() + sg[1] * d.y());
      // K_IJ = V B_I^T D B_J (plane strain, small strain)
      for (int l = 0; l < sp.n; ++l) {
        const Vec2& e = sp.dN[l];
        const Index J = sp.node[l];
        const double kxx = V * ((lambda_ + 2 * mu_) * d.x() * e.x() + mu_ * d.y() * e.y());
        const double kxy = V * (lambda_ * d.x() * e.y() + mu_ * d.y() * e.x());
        const double kyx = V * (lambda_ * d.y() * e.x() + mu_ * d.x() * e.y());
        const double kyy = V * ((lambda_ + 2 * mu_) * d.y() * e.y() + mu_ * d.x() * e.x());
        trip.emplace_back(2 * I, 2 * J, kxx);
        trip.emplace_back(2 * I, 2 * J + 1, kxy);
        trip.emplace_back(2 * I + 1, 2 * J, kyx);
        trip.emplace_back(2 * I + 1, 2 * J + 1, kyy);
      }
    }
  }
  {  // the loads at the end of the step
    std::vector<Vec2> fl(nn, Vec2::Zero());
    add_loads(fl, t_new_);
    for (Index I = 0; I < nn; ++I) fext.segment<2>(2 * I) += fl[I];
  }
  // Held dofs: empty nodes and fixed components; prescribed motion is not available implicitly.
  std::vector<char> held(2 * nn, 0);
  for (Index I = 0; I < nn; ++I)
    if (!(mass[I] > 0)) held[2 * I] = held[2 * I + 1] = 1;
  for (const auto& [node, comp] : fixed_) held[2 * node + comp] = 1;
  KinematicState s;
  s.t = t_;
  s.x = Vec::Zero(2 * nn);
  s.v = Vec::Zero(2 * nn);
  s.a = Vec::Zero(2 * nn);
  for (Index I = 0; I < nn; ++I) {
    s.x.segment<2>(2 * I) = origin_ + Vec2((I % (nx_ + 1)) * h_, (I / (nx_ + 1)) * h_);
    if (mass[I] > 0) {
      s.v.segment<2>(2 * I) = mv.segment<2>(2 * I) / mass[I];
      s.a.segment<2>(2 * I) = ma.segment<2>(2 * I) / mass[I];
    }
  }
  for (Index d = 0; d < 2 * nn; ++d)
    if (held[d]) s.v[d] = s.a[d] = 0.0;
  integrator_->begin_step(s, dt);
  const TangentCoefficients cf = integrator_->coefficients();
  SparseMatrix K(2 * nn, 2 * nn);
  K.setFromTriplets(trip.begin(), trip.end());
  // Linear: r(x) = M a(x) + fint0 + K (x_eval - x_n) - fext; one Newton step from the predictor.
  Vec x = integrator_->predictor();
  const EvalPoint ev = integrator_->kinematics(x);
  Vec r = Vec::Zero(2 * nn);
  for (Index I = 0; I < nn; ++I) r.segment<2>(2 * I) = mass[I] * ev.a.segment<2>(2 * I);
  r += fint0 + K * (ev.x - s.x) - fext;
  SparseMatrix H = cf.c_k * K;
  for (Index I = 0; I < nn; ++I)
    for (int c = 0; c < 2; ++c) H.coeffRef(2 * I + c, 2 * I + c) += cf.c_m * mass[I];
  for (int k = 0; k < H.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(H, k); it; ++it)
      if (held[it.row()] || held[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  for (Index d = 0; d < 2 * nn; ++d)
    if (held[d]) {
      r[d] = 0.0;
      if (H.coeff(d, d) == 0.0) H.coeffRef(d, d) = 1.0;
    }
  H.makeCompressed();
  solver_->factorize(H);
  Vec dx;
  solver_->solve(-r, dx);
  x += dx;
  KinematicState e;
  integrator_->end_step(x, e);
  // Grid to particles: FLIP velocity and acceleration, positions and stresses from the grid displacement.
  const Vec du = x - s.x;
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index q = 0; q < np; ++q) {
    const Support& sp = sup_[q];
    Vec2 dv = Vec2::Zero(), a = Vec2::Zero(), u = Vec2::Zero();
    Mat2 G = Mat2::Zero();  // grad of the displacement increment
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      dv += sp.N[k] * (e.v.segment<2>(2 * I) - s.v.segment<2>(2 * I));
      a += sp.N[k] * e.a.segment<2>(2 * I);
      u += sp.N[k] * du.segment<2>(2 * I);
      G += du.segment<2>(2 * I) * sp.dN[k].transpose();
    }
    P_.v[q] += dv;
    P_.a[q] = a;
    P_.x[q] += u;
    elastic_increment(q, G);
  }
}

IterationReport MpmModel::solve_iteration() {
  const auto t0 = Clock::now();
  if (implicit_) {
    step_implicit(dt_);
    t_ = t_new_;
    ++substeps_;
    times_.assembly += seconds_since(t0);
    IterationReport r;
    r.converged = true;
    r.residual_ref = 1;
    r.inner_iterations = 1;
    return r;
  }
  const double rho_sat = two_phase_ ? (1 - P_.n[0]) * rho_ + P_.n[0] * rho_w_ : rho_;
  const double c = std::sqrt((lambda_ + 2 * mu_ + (two_phase_ ? K_w_ / P_.n[0] : 0.0)) / rho_sat);
  const double dt_max = cfl_ * h_ / c;
  const int n = std::max(1, static_cast<int>(std::ceil(dt_ / dt_max * (1 - 1e-12))));
  const double dt = dt_ / n;
  for (int k = 0; k < n; ++k) {
    if (two_phase_) substep_two_phase(dt);
    else substep(dt);
    t_ += dt;
  }
  t_ = t_new_;
  substeps_ += n;
  times_.assembly += seconds_since(t0);
  IterationReport r;
  r.converged = true;
  r.residual = 0;
  r.residual_ref = 1;
  r.inner_iterations = n;
  return r;
}

void MpmModel::write_output(double t) {
  const auto t0 = Clock::now();
  if (!series_) series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_);
  VtpData d;
  d.points = P_.x;
  Field u{"displacement", 2, {}}, v{"velocity", 2, {}}, s{"stress", 4, {}}, vol{"volume", 1, {}},
      pl{"plastic_multiplier", 1, {}}, pw{"pore_pressure", 1, {}};
  for (size_t p = 0; p < P_.size(); ++p) {
    for (int c = 0; c < 2; ++c) {
      u.values.push_back(P_.x[p][c] - P_.X[p][c]);
      v.values.push_back(P_.v[p][c]);
    }
    for (double x : P_.stress[p]) s.values.push_back(x);
    vol.values.push_back(P_.volume[p]);
    pl.values.push_back(P_.plastic[p]);
    pw.values.push_back(-P_.p[p]);
  }
  d.point_fields = {u, v, s, vol, pl};
  if (two_phase_) d.point_fields.push_back(pw);
  series_->write(t, d);
  if (grid_output_) {
    // The grid of the last sub-step: nodes with mass, their mass, velocity and the force of that sub-step
    // (internal, gravity, loads, boundaries), and whether a component is fixed or prescribed.
    if (!grid_series_) grid_series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_ + "_grid");
    std::vector<int> held(gm_.size(), 0);
    for (const auto& [node, comp] : fixed_) held[node] |= 1 << comp;
    for (const auto& m : moving_) held[m.node] |= 4 << m.comp;
    VtpData g;
    Field mass{"mass", 1, {}}, vel{"velocity", 2, {}}, force{"force", 2, {}}, bc{"boundary", 1, {}};
    for (int j = 0; j <= ny_; ++j)
      for (int i = 0; i <= nx_; ++i) {
        const size_t n = static_cast<size_t>(j) * (nx_ + 1) + i;
        if (!(gm_[n] > 0)) continue;
        g.points.push_back(origin_ + Vec2(i * h_, j * h_));
        mass.values.push_back(gm_[n]);
        for (int c = 0; c < 2; ++c) {
          vel.values.push_back(gv_[n][c]);
          force.values.push_back(gf_[n][c]);
        }
        bc.values.push_back(held[n]);  // bits: 1 x fixed, 2 y fixed, 4 x prescribed, 8 y prescribed
      }
    g.point_fields = {mass, vel, force, bc};
    grid_series_->write(t, g);
  }
  if (particles_csv_) {
    const auto path = ctx_.out_dir / (name_ + "_particles.csv");
    const auto tmp = path.string() + ".tmp";
    {
      std::ofstream o(tmp);
      if (!o) throw std::runtime_error("cannot write " + tmp);
      o << "# " << name_ << " particles at t = " << t << "\nX,Y,x,y,vx,vy,sxx,syy,sxy,szz,volume,pore_pressure\n" << std::setprecision(12);
      for (size_t p = 0; p < P_.size(); ++p) {
        const auto& sg = P_.stress[p];
        o << P_.X[p].x() << "," << P_.X[p].y() << "," << P_.x[p].x() << "," << P_.x[p].y() << "," << P_.v[p].x() << ","
          << P_.v[p].y() << "," << sg[0] << "," << sg[1] << "," << sg[2] << "," << sg[3] << "," << P_.volume[p] << "," << -P_.p[p] << "\n";
      }
    }
    std::filesystem::rename(tmp, path);
  }
  times_.output += seconds_since(t0);
}

std::unique_ptr<Probe> MpmModel::make_probe(Params p) {
  const std::string t = p.choice("type", {"particle", "energy", "front", "height", "mean_pore_pressure"});
  if (t == "mean_pore_pressure") {  // sum p V / sum V over the body (compression positive)
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}});
    if (!two_phase_) p.fail("type", "body '" + name_ + "' is not two-phase");
    return std::make_unique<MpmProbe>(*this, p.string("name"), "mean_pore_pressure", -1);
  }
  if (t == "front") {  // the largest x of any particle (a run-out)
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}});
    return std::make_unique<MpmProbe>(*this, p.string("name"), "front", -1);
  }
  if (t == "height") {  // the largest y of the particles within `band` of the vertical line x
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"x", nullptr}, {"band", h_ / ppc_}});
    const double x = p.number("x"), x0 = origin_.x(), x1 = origin_.x() + nx_ * h_;
    if (!(x >= x0 && x <= x1)) {  // outside the grid no particle can be: nan at every step
      std::ostringstream os;
      os << "lies outside the grid (x from " << x0 << " to " << x1 << ")";
      p.fail("x", os.str());
    }
    auto probe = std::make_unique<MpmProbe>(*this, p.string("name"), "height", -1);
    probe->set_line(x, p.positive("band"));
    return probe;
  }
  if (t == "energy") {
    p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"kind", "total"}});
    return std::make_unique<MpmProbe>(*this, p.string("name"),
                                      p.choice("kind", {"kinetic", "strain", "total", "gravity_work"}), -1);
  }
  // The particle nearest to a reference position.
  p.validate({{"name", nullptr}, {"type", t}, {"body", nullptr}, {"at", nullptr}, {"quantity", "displacement_y"}});
  const std::string q = p.choice("quantity", {"displacement_x", "displacement_y", "velocity_x", "velocity_y",
                                              "stress_xx", "stress_yy", "stress_xy", "pore_pressure",
                                              "acceleration_x", "acceleration_y"});
  const Vec2 at = p.vec2("at");
  Index best = 0;
  for (size_t k = 1; k < P_.size(); ++k)
    if ((P_.X[k] - at).squaredNorm() < (P_.X[best] - at).squaredNorm()) best = static_cast<Index>(k);
  if ((P_.X[best] - at).norm() > h_) p.fail("at", "no particle within a cell of the point");
  return std::make_unique<MpmProbe>(*this, p.string("name"), q, best);
}

std::vector<double> MpmProbe::sample() const {
  const Particles& P = m_.particles();
  if (quantity_ == "mean_pore_pressure") {
    double pv = 0, v = 0;
    for (size_t k = 0; k < P.size(); ++k) {
      pv -= P.p[k] * P.volume[k];
      v += P.volume[k];
    }
    return {pv / v};
  }
  if (quantity_ == "front" || quantity_ == "height") {
    double best = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < P.size(); ++k) {
      if (quantity_ == "front") best = std::max(best, P.x[k].x());
      else if (std::abs(P.x[k].x() - x_) <= band_) best = std::max(best, P.x[k].y());
    }
    return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
  }
  if (p_ < 0) {
    if (quantity_ == "kinetic") return {m_.kinetic_energy()};
    if (quantity_ == "strain") return {m_.strain_energy()};
    if (quantity_ == "gravity_work") return {m_.gravity_work()};
    return {m_.kinetic_energy() + m_.strain_energy()};
  }
  if (quantity_ == "displacement_x") return {P.x[p_].x() - P.X[p_].x()};
  if (quantity_ == "displacement_y") return {P.x[p_].y() - P.X[p_].y()};
  if (quantity_ == "velocity_x") return {P.v[p_].x()};
  if (quantity_ == "velocity_y") return {P.v[p_].y()};
  if (quantity_ == "acceleration_x") return {P.a[p_].x()};
  if (quantity_ == "acceleration_y") return {P.a[p_].y()};
  if (quantity_ == "stress_xx") return {P.stress[p_][0]};
  if (quantity_ == "stress_yy") return {P.stress[p_][1]};
  if (quantity_ == "pore_pressure") return {-P.p[p_]};  // compression positive
  return {P.stress[p_][2]};
}

}  // namespace

std::unique_ptr<PhysicsModel> make_mpm_model(Params body, const CaseContext& ctx) {
  return std::make_unique<MpmModel>(std::move(body), ctx);
}

}  // namespace lagfsi
