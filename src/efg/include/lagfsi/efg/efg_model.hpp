#pragma once
/// @file efg_model.hpp
/// The EFG body (case-file type "efg") as a PhysicsModel: a static, physically nonlinear plane analysis with the
/// element-free Galerkin method (the INSANE EFG thesis; digest shared/spec/003_efg.md).
///
/// Unknowns: the MLS nodal parameters V (2 per node; "unified" nodes = the background cells' corners) and, with
/// Lagrange multipliers, one multiplier per constrained component. Essential boundary conditions (per body,
/// "essential"):
///  - "coupling" (default, the thesis's method): the nodes of the supports are active FE nodes; every cell touching
///    one is a Q4 coupling element sharing its Gauss points; the MLS functions are corrected (Huerta &
///    Fernandez-Mendez 2000) so that FE + EFG reproduce the basis, and the conditions act directly on the dofs of the
///    active nodes (there v = u). "fe_nodes" (node selections) makes more nodes active without holding them: a cell
///    all of whose nodes are active, where the FE functions reproduce the basis (Q4 cells and the bilinear basis, Q9
///    cells and the biquadratic one), has corrected MLS functions zero to round-off, so it is the finite element:
///    [{"type": "all"}] turns the body into the FE model (Q4 or Q9) with the body's Gauss rule;
///  - "penalty": u^h(x_k) = u_k at the selected nodes by a penalty beta E (point collocation);
///  - "lagrange": the same constraints by Lagrange multipliers (collocation; an indefinite system: umfpack/klu).
/// Loading: a reference load P (tractions on cell edges) and prescribed displacements, both times the load factor
/// lambda, which the path-following control owns (path_following.hpp); one driver step = one load step (a failed
/// step is retried by the driver with a shorter increment; the material history is committed only at
/// finalize_step). Each Newton iteration assembles K (tangent or secant operator) and the internal force.
/// Runaway steps: the damage laws keep a floor of stiffness (damage <= 1 - 1e-9, a smeared crack's residual
/// strength and shear modulus), so a load beyond the body's capacity still finds an "equilibrium", at strains of
/// order sigma / (1e-9 E0), displacements orders of magnitude beyond the body's size. The analysis is geometrically
/// linear: a converged step whose nodal displacement exceeds the body's size (the diagonal of its bounding box) is
/// refused with a SolverError naming the control (load control: past the limit point; the others: the increment is far
/// too large), so the driver cuts the step back and, failing that, the run stops with that message. A step that does
/// not converge in the iterations allowed (under load control the tangent operator's way of failing past the peak),
/// and a non-finite or singular system, are reported the same way, at the control's path; a tolerance below
/// round-off is reported at /analysis/newton/residual_tolerance. Input the set-up can judge is an InputError at its
/// path: supports that leave a rigid motion free, shape functions that cannot be built (/bodies/i/efg), a body with
/// neither load nor prescribed displacement, a region that takes no cell, more cells or points than a run holds.
///
/// Shape functions, derivatives and supports are computed once per Gauss point and cached (thesis §4.4).
#include <lagfsi/case.hpp>
#include <lagfsi/efg/discretization.hpp>
#include <lagfsi/efg/material.hpp>
#include <lagfsi/efg/mls.hpp>
#include <lagfsi/efg/path_following.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/vtk_output.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::efg {

/// Analytical solutions for boundary data and the energy-norm error (the benchmarks).
struct ExactSolution {
  std::string type = "none";  ///< "none", "timoshenko" (cantilever, parabolic end shear), "kirsch" (plate with hole),
                              ///< "polynomial" (u_x, u_y quadratic polynomials: patch tests)
  double cx[6] = {0, 0, 0, 0, 0, 0}, cy[6] = {0, 0, 0, 0, 0, 0};  ///< polynomial: coefficients of 1, x, y, x^2, xy, y^2
  double P = 0, L = 0, D = 0;  ///< Timoshenko & Goodier: load, length, depth (x from the clamped end, y centred)
  double sigma0 = 0, a = 0;    ///< Kirsch: remote stress in x, hole radius
  double E = 1, nu = 0;
  bool available() const { return type != "none"; }
  Vec3 stress(const Vec2& x) const;
  Vec2 displacement(const Vec2& x) const;  ///< Timoshenko and polynomial
  Vec2 body_force(const Vec2& x) const;    ///< -div sigma (polynomial; zero for the others)
};

class EfgModel final : public PhysicsModel {
 public:
  EfgModel(Params body, const CaseContext& ctx);
  std::string name() const override { return name_; }
  std::string type() const override { return "efg"; }
  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  void finalize_step() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;
  Index num_nodes() const override { return mesh_.num_nodes(); }
  Index num_elements() const override { return mesh_.num_cells(); }
  Json summary() const override;
  bool can_checkpoint() const override { return true; }
  /// The committed state, the material history, the control's memory and the output series (efg_checkpoint.cpp).
  void serialize(StateArchive& ar) override;

  // Read access for probes and tests.
  double load_factor() const { return lambda0_; }
  const Vec& parameters() const { return x0_; }
  /// Nodal displacements U = f(V) of the committed state (2 per node).
  Vec nodal_displacements() const;
  const Vec& reference_load() const { return Ptr_; }
  /// Material internal force minus lambda P at the committed state (the reactions at supports).
  Vec reactions() const;
  const QuadMesh& mesh() const { return mesh_; }
  /// Energy-norm error against the exact solution: absolute and relative (NaN without one).
  std::pair<double, double> energy_error() const;

 private:
  // input (efg_input.cpp)
  void read_discretization(Params b);
  void read_boundary_conditions(Params b);
  void read_loads(Params b);
  void read_control(Params b);
  // setup (efg_setup.cpp)
  void build_integration_points();
  void build_pattern();
  /// Shape functions at natural coordinates (xi, eta) of cell c (coupled where the cell is a coupling element).
  void shape_at(Index c, double xi, double eta, ShapeValues& out, bool derivatives) const;
  // assembly (efg_assembly.cpp)
  /// Internal force and (if K) the operator at parameters x, trial histories into hist1_.
  void assemble(const Vec& x, Vec& fint, bool with_matrix);
  /// Solves K dx = rhs with dofs fixed to `fixed_values` (nullptr: zero); K is factorized by factorize().
  void factorize();
  Vec solve(const Vec& rhs, bool with_prescribed);
  Vec to_control(const Vec& dx) const;  ///< U or V form vector of the control
  // path following (efg_model.cpp)
  /// Throws SolverError when the converged iterate x_ lies at a displacement beyond the body's size.
  void check_runaway() const;
  bool linear_elastic() const;  ///< the body's material and every region's are linear elastic
  /// Throws SolverError "<control's path>: reason" (a step that cannot be solved, named where it was asked for);
  /// overflow_hint adds the likely causes of non-finite numbers and singular matrices.
  [[noreturn]] void fail_solve(const std::string& reason, bool overflow_hint = false) const;
  /// Throws InputError "<body's path>/key: reason" (key empty: the body).
  [[noreturn]] void fail_input(const std::string& key, const std::string& reason) const;

  std::string name_;
  std::string file_, path_;  // the case file and the body's JSON path (/bodies/i), for messages
  CaseContext ctx_;
  QuadMesh mesh_;
  std::vector<Vec2> rho_;
  MlsShape mls_;
  Visibility vis_;
  NodeSearch search_;
  double rho_max_ = 0, thickness_ = 1;
  double body_size_ = 1;  // diagonal of the nodes' bounding box
  int gauss_ = 2;
  bool consistent_ = false;  // integration-consistent derivative correction (integration.hpp)
  std::unique_ptr<Material> material_;
  std::vector<std::unique_ptr<Material>> region_materials_;
  std::vector<std::array<Vec2, 2>> region_boxes_;
  std::vector<int> cell_material_;  // -1: body material, else index into region_materials_
  Operator operator_ = Operator::tangent;
  ExactSolution exact_;

  // essential conditions
  std::string essential_ = "coupling";
  std::vector<char> active_;         // per node: an active FE node (coupling)
  std::vector<char> coupling_cell_;  // per cell
  std::vector<Index> fixed_dofs_;    // coupling: dofs held directly
  std::vector<double> fixed_ref_;    // their values at lambda = 1
  struct Constraint {
    Index node;
    int comp;
    double value;
    ShapeValues sh;
  };
  std::vector<Constraint> constraints_;  // penalty / lagrange collocation
  double penalty_ = 0;

  // integration points (flat shape data)
  struct GaussPoint {
    Vec2 x;
    double w;
    Index cell;
    Index begin, n;
  };
  std::vector<GaussPoint> gps_;
  std::vector<Index> gnode_;
  std::vector<double> gN_, gNx_, gNy_;
  std::vector<int> gloc_;                       // position of the node in its cell's union
  std::vector<std::vector<Index>> cell_nodes_;  // union of the supports of the cell's points (sorted)
  std::vector<Index> cell_gp_begin_;
  double min_rcond_ = 1, t_shape_ = 0;
  int max_support_ = 0;
  double mean_support_ = 0;

  // nodal evaluation U = f(V): per node its support and values
  std::vector<std::vector<std::pair<Index, double>>> node_eval_;

  // system
  Index ndof_ = 0, nsys_ = 0;  // 2 n, plus multipliers
  SparseMatrix K_;
  std::unique_ptr<LinearSolver> solver_;
  Vec P_;         // reference vector at lambda = 1 (loads + penalty / Lagrange prescribed values)
  Vec Ptr_;       // its applied-load part (tractions)
  Vec fint0_;     // internal force (with constraint terms) of the committed state
  Vec Kfix_ref_;  // K_:,fixed * fixed_ref (before elimination)
  std::vector<char> is_fixed_;

  // state
  Vec x0_, x_, fint_;
  double lambda0_ = 0, lambda_ = 0;
  std::vector<History> hist0_, hist1_;
  PathFollowing control_;
  bool control_u_form_ = false;
  Index control_dof_ = -1;
  int iter_ = 0;
  double step_scale_ = 1;
  Vec dx_step_;
  double lambda_peak_ = 0;
  int steps_ = 0;

  std::unique_ptr<PvdSeries> series_, gauss_series_;
  friend class EfgProbeAccess;
};

}  // namespace lagfsi::efg

namespace lagfsi {

/// The EFG body's builder (registered as "efg" in model_registry() of the app layer, model_registry.hpp).
std::unique_ptr<PhysicsModel> make_efg_model(Params body, const CaseContext& ctx);

}  // namespace lagfsi
