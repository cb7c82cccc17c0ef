// EFG body input: background cells and nodes, MLS settings, materials and regions, essential conditions
// (coupling, penalty, Lagrange), loads and the path-following control, read from /bodies/i of type "efg"
// (the cached integration points and the matrix pattern: efg_setup.cpp). See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>

#include <lagfsi/error.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace lagfsi::efg {

namespace {

const KeyTable kEfgKeys(
    "/bodies/* (type efg)",
    "An element-free Galerkin body: a static, physically nonlinear plane analysis (MLS shape functions).",
    {{"name", nullptr, "Body name (output files; probes refer to it)."},
     {"type", "efg", "`efg` (needs a static analysis)."},
     {"thickness", 1.0, "Out-of-plane thickness (m)."},
     {"domain", nullptr, "The nodes and background cells (see /bodies/*/domain (efg body, ...))."},
     {"material", nullptr, "The material (see /bodies/*/material (efg body, type linear_elastic) and others)."},
     {"regions", Json::array(), "Boxes with another material (see /bodies/*/regions/* (efg body))."},
     {"efg", Json::object(), "Shape functions and integration (see /bodies/*/efg (efg body))."},
     {"essential", Json::object(), "How essential conditions are imposed (see /bodies/*/essential (efg body))."},
     {"exact", Json::object(), "An analytical solution for boundary data and errors (see /bodies/*/exact (efg body))."},
     {"boundary_conditions", Json::array(), "Held displacements (see /bodies/*/boundary_conditions/* (efg body))."},
     {"loads", Json::array(), "The reference load (see /bodies/*/loads/* (efg body, ...))."},
     {"operator", "tangent", "Newton operator: tangent or secant."},
     {"control", Json::object(), "Path following (see /bodies/*/control (efg body))."}});

const KeyTable kEfgRegionKeys("/bodies/*/regions/* (efg body)", "An axis-aligned box of another material.",
                              {{"min", nullptr, "Lower-left corner [x, y] (m)."},
                               {"max", nullptr, "Upper-right corner [x, y] (m)."},
                               {"material", nullptr,
                                "Its material (see /bodies/*/material (efg body, type linear_elastic) and others)."}});

const KeyTable kEfgExactKeys(
    "/bodies/*/exact (efg body)", "An analytical solution (boundary data, energy-norm error).",
    {{"type", "none",
      "none, timoshenko (cantilever under a parabolic end shear), kirsch (plate with a hole) or polynomial "
      "(quadratic u_x, u_y: patch tests)."},
     {"P", 0.0, "timoshenko: end load (N)."},
     {"L", 0.0, "timoshenko: length (m), x from the clamped end."},
     {"D", 0.0, "timoshenko: depth (m), y centred."},
     {"sigma0", 0.0, "kirsch: remote stress in x (Pa)."},
     {"radius", 0.0, "kirsch: hole radius (m)."},
     {"ux", Json::array({0, 0, 0, 0, 0, 0}), "polynomial: coefficients of 1, x, y, x^2, xy, y^2 in u_x."},
     {"uy", Json::array({0, 0, 0, 0, 0, 0}), "polynomial: coefficients of 1, x, y, x^2, xy, y^2 in u_y."}});

const KeyTable kEfgRectangleKeys(
    "/bodies/*/domain (efg body, type rectangle)", "A rectangle of cells, possibly minus boxes.",
    {{"type", "rectangle", "`rectangle`."},
     {"origin", Json::array({0.0, 0.0}), "Lower-left corner [x, y] (m)."},
     {"size", nullptr, "Width and height [w, h] (m)."},
     {"divisions", nullptr, "Cells [nx, ny]."},
     {"holes", Json::array(), "Boxes without cells (see /bodies/*/domain/holes/* (efg body))."},
     {"cells", "q4", "Background cells: q4 or q9 (nodes at the corners, or also at mid-sides and centres)."}});

const KeyTable kEfgHoleKeys("/bodies/*/domain/holes/* (efg body)", "A box removed from the rectangle.",
                            {{"min", nullptr, "Lower-left corner [x, y] (m)."},
                             {"max", nullptr, "Upper-right corner [x, y] (m)."}});

const KeyTable kEfgPlateKeys("/bodies/*/domain (efg body, type plate_with_hole)",
                             "A quarter of a square plate [0, size]^2 with a circular hole at the origin.",
                             {{"type", "plate_with_hole", "`plate_with_hole`."},
                              {"radius", nullptr, "Hole radius (m)."},
                              {"size", nullptr, "Side of the quarter plate (m)."},
                              {"divisions", nullptr,
                               "Cells [n_arc, n_radial]: along each half of the arc, and radially."},
                              {"grading", 1.0, "Ratio of the outermost to the innermost radial cell size."}});

const KeyTable kEfgSettingsKeys(
    "/bodies/*/efg (efg body)", "The MLS shape functions and the integration.",
    {{"basis", "bilinear", "Polynomial basis: linear, bilinear, quadratic or biquadratic."},
     {"weight", "cubic_spline", "Weight function: cubic_spline, quartic_spline, exponential or quartic_alt."},
     {"domain", "rectangular", "Influence domains: rectangular or circular."},
     {"alpha", 2.0, "Domain size: alpha times the node spacing."},
     {"gauss", 5, "Gauss points per direction in each cell, 1-12."},
     {"integration", "gauss", "gauss, or consistent (derivatives corrected per cell)."},
     {"rcond_min", 1e-12, "Smallest reciprocal condition number of the moment matrix."},
     {"protected_segments", Json::array(),
      "Segments the supports do not cross (visibility; see /bodies/*/efg/protected_segments/* (efg body))."}});

const KeyTable kEfgSegmentKeys("/bodies/*/efg/protected_segments/* (efg body)",
                               "A segment (a crack, a re-entrant corner's side) no support crosses.",
                               {{"from", nullptr, "One end [x, y] (m)."},
                                {"to", nullptr, "The other end [x, y] (m)."}});

const KeyTable kEfgEssentialKeys(
    "/bodies/*/essential (efg body)", "How essential boundary conditions are imposed.",
    {{"method", "coupling",
      "coupling (FE nodes at the supports, coupled to EFG), penalty (collocation) or lagrange (multipliers; "
      "umfpack or klu)."},
     {"penalty", 1e4, "Penalty factor, times Young's modulus."},
     {"fe_nodes", Json::array(),
      "coupling: node selections made FE nodes without holding them ([{\"type\": \"all\"}]: the FE model)."}});

const KeyTable kEfgBcKeys("/bodies/*/boundary_conditions/* (efg body)", "Held displacements, times the load factor.",
                          {{"type", nullptr, "fixed, prescribed (value) or exact (the exact solution's)."},
                           {"select", nullptr, "The nodes (see selection (type point) and others)."},
                           {"components", "xy", "x, y or xy."},
                           {"value", Json::array({0.0, 0.0}), "prescribed: displacement [x, y] (m)."}});

const KeyTable kEfgBodyForceKeys("/bodies/*/loads/* (efg body, type exact_body_force)",
                                 "The exact solution's body force.",
                                 {{"type", "exact_body_force", "`exact_body_force`."}});

const KeyTable kEfgTractionKeys(
    "/bodies/*/loads/* (efg body, type traction or exact_traction)",
    "A traction on the cell edges of the selected nodes, or the exact solution's.",
    {{"type", nullptr, "traction or exact_traction."},
     {"select", nullptr, "The boundary nodes (see selection (type point) and others)."},
     {"value", Json::array({0.0, 0.0}), "traction: [x, y] (Pa), the peak of a non-uniform profile."},
     {"profile", "uniform", "uniform, parabolic or triangular (along a segment selection)."}});

const KeyTable kEfgControlKeys(
    "/bodies/*/control (efg body)", "Path following: the load factor of each load step.",
    {{"type", "load", "load, displacement, generalized_displacement or arc_length."},
     {"form", "V", "Control space: U (nodal displacements) or V (MLS parameters)."},
     {"increment", 0.0, "Initial load factor or displacement increment; 0 with load control: the analysis' load step."},
     {"at", Json::array({0.0, 0.0}), "displacement control: the node [x, y] (m) whose displacement is controlled."},
     {"component", "y", "displacement control: x or y."},
     {"complex_roots", "real_part", "Arc length with complex roots: real_part, normal_plane or cut_back."}});

}  // namespace

namespace {
Vec2 box_corner(Params p, const std::string& key) { return p.vec2(key); }

/// The two cell counts of a domain: positive integers, checked in floating point before any conversion, and a
/// number of cells a run can hold (each cell carries gauss^2 points with some 16-40 support nodes each).
std::vector<double> divisions(const Params& d, const std::string& expected) {
  const auto div = d.numbers("divisions");
  if (div.size() != 2 || div[0] < 1 || div[1] < 1 || div[0] != std::floor(div[0]) || div[1] != std::floor(div[1]))
    d.fail("divisions", expected);
  if (div[0] * div[1] > 1e6) d.fail("divisions", "more than a million background cells");
  return div;
}

/// Why the held components leave the body free to move, or "" when they fix it. A rigid motion
/// u = (a - theta (y - yc), b + theta (x - xc)) that every held component leaves at zero is free: the body's
/// stiffness is singular and no load step can be solved.
std::string rigid_motion_left(const std::vector<Index>& held_dofs, const std::vector<Vec2>& nodes) {
  Vec2 lo = nodes.front(), hi = lo, c = Vec2::Zero();
  for (const Vec2& p : nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    c += p;
  }
  c /= static_cast<double>(nodes.size());
  const double L = std::max((hi - lo).norm(), 1e-300);
  Mat3 M = Mat3::Zero();  // sum of r r^T over the held components' rows r (a, b, theta L)
  for (Index d : held_dofs) {
    const Vec2 x = (nodes[d / 2] - c) / L;
    const Vec3 r = d % 2 == 0 ? Vec3(1, 0, -x.y()) : Vec3(0, 1, x.x());
    M += r * r.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig(M);
  if (eig.eigenvalues()[0] > 1e-10 * std::max(1.0, eig.eigenvalues()[2])) return "";
  // With components held in both directions no translation is free: the free motion is a rotation.
  if (M(0, 0) == 0) return "a rigid translation in x";
  if (M(1, 1) == 0) return "a rigid translation in y";
  return "a rigid rotation";
}
}  // namespace

EfgModel::EfgModel(Params b, const CaseContext& ctx) : ctx_(ctx) {
  b.validate(kEfgKeys);
  file_ = b.file();
  path_ = b.path();
  name_ = b.identifier("name");
  thickness_ = b.positive("thickness");
  if (ctx.analysis.type != "static")
    b.at("type").fail("an efg body needs a static analysis (analysis.type = \"static\")");
  material_ = make_material(b.at("material"));
  Params regions = b.at("regions");
  for (size_t i = 0; i < regions.size(); ++i) {
    Params r = regions.at(i);
    r.validate(kEfgRegionKeys);
    region_boxes_.push_back({box_corner(r, "min"), box_corner(r, "max")});
    region_materials_.push_back(make_material(r.at("material")));
  }
  operator_ = b.choice("operator", {"tangent", "secant"}) == "tangent" ? Operator::tangent : Operator::secant;
  Params ex = b.at("exact");
  ex.validate(kEfgExactKeys);
  exact_.type = ex.choice("type", {"none", "timoshenko", "kirsch", "polynomial"});
  if (exact_.type == "polynomial")
    for (const char* k : {"ux", "uy"}) {
      const auto c = ex.numbers(k);
      if (c.size() != 6) ex.fail(k, "expected 6 coefficients (of 1, x, y, x^2, xy, y^2)");
      for (int i = 0; i < 6; ++i) (k[1] == 'x' ? exact_.cx : exact_.cy)[i] = c[i];
    }
  exact_.E = material_->young();
  exact_.nu = material_->poisson();
  if (material_->plane_strain()) {  // the formulas are plane stress: E -> E/(1-nu^2), nu -> nu/(1-nu)
    exact_.E = exact_.E / (1 - exact_.nu * exact_.nu);
    exact_.nu = exact_.nu / (1 - exact_.nu);
  }
  if (exact_.type == "timoshenko") {
    exact_.P = ex.number("P");
    exact_.L = ex.positive("L");
    exact_.D = ex.positive("D");
  } else if (exact_.type == "kirsch") {
    exact_.sigma0 = ex.number("sigma0");
    exact_.a = ex.positive("radius");
  }
  read_discretization(b);
  read_boundary_conditions(b);
  try {
    // An MLS failure here (a point no influence domain covers, a degenerate moment matrix) comes from the
    // discretization the input asks for: the domain, the supports' size (alpha) or the protected segments.
    build_integration_points();
    read_loads(b);
  } catch (const SolverError& e) {
    fail_input("efg", std::string("the shape functions cannot be built: ") + e.what());
  }
  read_control(b);
  build_pattern();
  solver_ = make_linear_solver(ctx.analysis.linear_solver);
  const bool unsym = (operator_ == Operator::tangent && !material_->linear()) || (material_->type() == "smeared_crack");
  if (solver_->symmetric_only() && (essential_ == "lagrange" || unsym))
    b.at(essential_ == "lagrange" ? "essential" : "operator")
        .fail(std::string(essential_ == "lagrange" ? "Lagrange multipliers give an indefinite system"
                                                   : "this operator is unsymmetric") +
              ": set analysis.linear_solver.type to umfpack or klu");
}

void EfgModel::read_discretization(Params b) {
  Params d = b.at("domain");
  if (!d.json().is_object() || !d.has("type")) d.fail("type", "required key is missing");
  const std::string t = d.choice("type", {"rectangle", "plate_with_hole"});
  try {
    if (t == "rectangle") {
      d.validate(kEfgRectangleKeys);
      const int order = d.choice("cells", {"q4", "q9"}) == "q9" ? 2 : 1;
      const Vec2 size = d.vec2("size");
      if (!(size.x() > 0 && size.y() > 0)) d.fail("size", "must be positive");
      const auto div = divisions(d, "expected [nx, ny], positive integers");
      std::vector<std::array<Vec2, 2>> holes;
      Params h = d.at("holes");
      for (size_t i = 0; i < h.size(); ++i) {
        Params hi = h.at(i);
        hi.validate(kEfgHoleKeys);
        holes.push_back({hi.vec2("min"), hi.vec2("max")});
      }
      mesh_ = rectangle_grid(d.vec2("origin"), size, static_cast<int>(div[0]), static_cast<int>(div[1]), holes, order);
    } else {
      d.validate(kEfgPlateKeys);
      const auto div = divisions(d, "expected [n_arc, n_radial], positive integers");
      mesh_ = plate_with_hole(d.positive("radius"), d.positive("size"), static_cast<int>(div[0]),
                              static_cast<int>(div[1]), d.positive("grading"));
    }
  } catch (const std::invalid_argument& e) {
    d.fail(e.what());
  }
  Params e = b.at("efg");
  e.validate(kEfgSettingsKeys);
  consistent_ = e.choice("integration", {"gauss", "consistent"}) == "consistent";
  Basis basis;
  basis.type = Basis::parse(e.choice("basis", Basis::names()));
  InfluenceDomain dom;
  dom.weight.type = Weight::parse(e.choice("weight", Weight::names()));
  dom.shape =
      e.choice("domain", {"rectangular", "circular"}) == "circular" ? DomainShape::circular : DomainShape::rectangular;
  const double alpha = e.positive("alpha");
  gauss_ = e.integer("gauss", 1);
  if (gauss_ > 12) e.fail("gauss", "at most 12 points per direction");
  if (static_cast<double>(mesh_.num_cells()) * gauss_ * gauss_ > 4e6)
    e.fail("gauss", "more than 4 million integration points (background cells x gauss^2)");
  const double rcond_min = e.positive("rcond_min");
  if (!(rcond_min < 1)) e.fail("rcond_min", "a reciprocal condition number: must lie in (0, 1)");
  mls_ = MlsShape(basis, dom, rcond_min);
  Params segs = e.at("protected_segments");
  for (size_t i = 0; i < segs.size(); ++i) {
    Params s = segs.at(i);
    s.validate(kEfgSegmentKeys);
    vis_.segments.push_back({s.vec2("from"), s.vec2("to")});
  }
  // rho_j = alpha h_j, h_j the largest node spacing (width / height of the cells, halved for Q9 cells) at node j.
  const Index nn = mesh_.num_nodes();
  std::vector<Vec2> h(nn, Vec2::Zero());
  const int npc = mesh_.nodes_per_cell();
  for (Index c = 0; c < mesh_.num_cells(); ++c) {
    Vec2 lo = mesh_.nodes[mesh_.cells[c][0]], hi = lo;
    for (Index n : mesh_.cells[c]) {
      lo = lo.cwiseMin(mesh_.nodes[n]);
      hi = hi.cwiseMax(mesh_.nodes[n]);
    }
    const Vec2 spacing = (hi - lo) / (mesh_.quadratic() ? 2.0 : 1.0);
    for (int a = 0; a < npc; ++a) h[mesh_.cell_node(c, a)] = h[mesh_.cell_node(c, a)].cwiseMax(spacing);
  }
  rho_.resize(nn);
  for (Index i = 0; i < nn; ++i) {
    rho_[i] = alpha * h[i];
    if (dom.shape == DomainShape::circular) rho_[i] = Vec2::Constant(alpha * h[i].maxCoeff());
    rho_max_ = std::max(rho_max_, rho_[i].maxCoeff());
  }
  search_ = NodeSearch(mesh_.nodes, rho_max_);
  cell_material_.assign(mesh_.num_cells(), -1);
  for (Index c = 0; c < mesh_.num_cells(); ++c) {
    Vec2 ctr = Vec2::Zero();
    for (Index n : mesh_.cells[c]) ctr += 0.25 * mesh_.nodes[n];
    for (size_t r = 0; r < region_boxes_.size(); ++r)
      if ((ctr.array() > region_boxes_[r][0].array()).all() && (ctr.array() < region_boxes_[r][1].array()).all())
        cell_material_[c] = static_cast<int>(r);
  }
  // A region that takes no cell would leave the body's material where the input asks for another.
  for (size_t r = 0; r < region_boxes_.size(); ++r)
    if (std::find(cell_material_.begin(), cell_material_.end(), static_cast<int>(r)) == cell_material_.end())
      b.at("regions").at(r).fail("the region (min, max) contains no background cell's centre");
}

void EfgModel::read_boundary_conditions(Params b) {
  Params es = b.at("essential");
  es.validate(kEfgEssentialKeys);
  essential_ = es.choice("method", {"coupling", "penalty", "lagrange"});
  penalty_ = es.positive("penalty") * material_->young();
  const Index nn = mesh_.num_nodes();
  active_.assign(nn, 0);
  coupling_cell_.assign(mesh_.num_cells(), 0);
  std::vector<double> value(2 * nn, 0.0);
  std::vector<char> held(2 * nn, 0);
  Params bcs = b.at("boundary_conditions");
  for (size_t i = 0; i < bcs.size(); ++i) {
    Params c = bcs.at(i);
    if (!c.json().is_object() || !c.has("type")) c.fail("type", "required key is missing");
    const std::string t = c.choice("type", {"fixed", "prescribed", "exact"});
    c.validate(kEfgBcKeys);
    const std::string comps = c.choice("components", {"x", "y", "xy"});
    if (t == "exact" && exact_.type != "timoshenko" && exact_.type != "polynomial")
      c.fail("type", "\"exact\" displacements need exact.type = timoshenko or polynomial");
    const Vec2 v = c.vec2("value");
    for (Index n : select_nodes(c.at("select"), mesh_.nodes)) {
      const Vec2 u = t == "exact" ? exact_.displacement(mesh_.nodes[n]) : (t == "prescribed" ? v : Vec2::Zero());
      for (int k = 0; k < 2; ++k)
        if (comps.find(k == 0 ? 'x' : 'y') != std::string::npos) {
          held[2 * n + k] = 1;
          value[2 * n + k] = u[k];
        }
      active_[n] = 1;
    }
  }
  for (Index d = 0; d < 2 * nn; ++d)
    if (held[d]) {
      fixed_dofs_.push_back(d);
      fixed_ref_.push_back(value[d]);
    }
  // A static analysis of a body its supports do not hold has no unique answer (a singular stiffness).
  const std::string free_motion = rigid_motion_left(fixed_dofs_, mesh_.nodes);
  if (!free_motion.empty())
    bcs.fail("the held components leave the body free to move (" + free_motion +
             "): hold more components (two in x at different heights, or two in y at different x, and one in the "
             "other direction)");
  // Active FE nodes that hold nothing (a node selection each; {"type": "all"}: the FE mesh everywhere).
  Params fe = es.at("fe_nodes");
  if (!fe.json().is_array()) es.fail("fe_nodes", "expected an array of node selections");
  if (fe.size() > 0 && essential_ != "coupling") es.fail("fe_nodes", "active FE nodes need method = \"coupling\"");
  for (size_t i = 0; i < fe.size(); ++i)
    for (Index n : select_nodes(fe.at(i), mesh_.nodes)) active_[n] = 1;
  if (essential_ == "coupling") {
    for (Index c = 0; c < mesh_.num_cells(); ++c)
      for (int a = 0; a < mesh_.nodes_per_cell(); ++a)
        if (active_[mesh_.cell_node(c, a)]) coupling_cell_[c] = 1;
  } else {
    std::fill(active_.begin(), active_.end(), 0);
  }
}

void EfgModel::read_loads(Params b) {
  const Index nn = mesh_.num_nodes();
  ndof_ = 2 * nn;
  // Collocation constraints (penalty, Lagrange).
  if (essential_ != "coupling") {
    for (size_t i = 0; i < fixed_dofs_.size(); ++i) {
      const Index n = fixed_dofs_[i] / 2;
      Constraint c{n, static_cast<int>(fixed_dofs_[i] % 2), fixed_ref_[i], {}};
      for (const auto& [j, v] : node_eval_[n]) {
        c.sh.nodes.push_back(j);
        c.sh.N.push_back(v);
      }
      constraints_.push_back(std::move(c));
    }
  }
  nsys_ = ndof_ + (essential_ == "lagrange" ? static_cast<Index>(constraints_.size()) : 0);
  P_ = Vec::Zero(nsys_);
  const auto edges = boundary_cell_edges(mesh_);
  std::vector<double> gx, gw;
  gauss_legendre(std::max(2, gauss_), gx, gw);
  Params loads = b.at("loads");
  ShapeValues sh;
  for (size_t i = 0; i < loads.size(); ++i) {
    Params l = loads.at(i);
    if (!l.json().is_object() || !l.has("type")) l.fail("type", "required key is missing");
    const std::string t = l.choice("type", {"traction", "exact_traction", "exact_body_force"});
    if (t == "exact_body_force") {
      l.validate(kEfgBodyForceKeys);
      if (!exact_.available()) l.fail("type", "exact_body_force needs an exact solution (exact.type)");
      for (const auto& gp : gps_) {
        const Vec2 bf = exact_.body_force(gp.x);
        for (Index k = 0; k < gp.n; ++k) {
          const Index j = gp.begin + k;
          P_[2 * gnode_[j]] += gN_[j] * bf.x() * gp.w;
          P_[2 * gnode_[j] + 1] += gN_[j] * bf.y() * gp.w;
        }
      }
      continue;
    }
    l.validate(kEfgTractionKeys);
    // (the edge rule is the one of the consistent-integration correction: interior edges cancel, boundary ones match)
    if (t == "exact_traction" && !exact_.available())
      l.fail("type", "exact_traction needs an exact solution (exact.type)");
    const std::string profile = l.choice("profile", {"uniform", "parabolic", "triangular"});
    const Vec2 value = l.vec2("value");
    Params sel = l.at("select");
    const auto nodes = select_nodes(sel, mesh_.nodes);
    Vec2 from = Vec2::Zero(), to = Vec2::Zero();
    if (profile != "uniform") {
      if (sel.string("type") != "segment") l.fail("profile", "a non-uniform profile needs a segment selection");
      from = sel.vec2("from");
      to = sel.vec2("to");
    }
    const std::set<Index> in(nodes.begin(), nodes.end());
    int used = 0;
    for (const auto& e : edges) {
      const Index c = e[0];
      const int k = e[1];
      const Index a = mesh_.cells[c][k], bnode = mesh_.cells[c][(k + 1) % 4];
      if (!in.count(a) || !in.count(bnode)) continue;
      ++used;
      // Natural coordinates along the edge k: corners (-1,-1), (1,-1), (1,1), (-1,1).
      static const double cxi[4] = {-1, 1, 1, -1}, ceta[4] = {-1, -1, 1, 1};
      const Vec2 pa = mesh_.nodes[a], pb = mesh_.nodes[bnode];
      const Vec2 normal = Vec2((pb - pa).y(), -(pb - pa).x()).normalized();
      const double half = 0.5 * (pb - pa).norm();
      for (size_t q = 0; q < gx.size(); ++q) {
        const double s = 0.5 * (1 + gx[q]);
        const double xi = cxi[k] + s * (cxi[(k + 1) % 4] - cxi[k]), eta = ceta[k] + s * (ceta[(k + 1) % 4] - ceta[k]);
        const Vec2 x = pa + s * (pb - pa);
        Vec2 tr;
        if (t == "exact_traction") {
          const Vec3 sg = exact_.stress(x);
          tr = Vec2(sg[0] * normal.x() + sg[2] * normal.y(), sg[2] * normal.x() + sg[1] * normal.y());
        } else {
          double f = 1;
          if (profile != "uniform") {
            const Vec2 d = to - from;
            const double r = std::clamp((x - from).dot(d) / d.squaredNorm(), 0.0, 1.0);
            f = profile == "parabolic" ? 6 * r * (1 - r) : 2 * r;
          }
          tr = f * value;
        }
        shape_at(c, xi, eta, sh, false);
        const double w = gw[q] * half * thickness_;
        for (size_t m = 0; m < sh.nodes.size(); ++m) {
          P_[2 * sh.nodes[m]] += sh.N[m] * tr.x() * w;
          P_[2 * sh.nodes[m] + 1] += sh.N[m] * tr.y() * w;
        }
      }
    }
    if (used == 0) sel.fail("the selection contains no boundary edge of the background cells");
  }
  Ptr_ = P_;
  // Nothing to follow: every load step would find the unloaded state (or, under path following, fail).
  if (!(P_.cwiseAbs().maxCoeff() > 0) &&
      std::all_of(fixed_ref_.begin(), fixed_ref_.end(), [](double v) { return v == 0.0; }))
    b.at("loads").fail("the body is neither loaded nor given a displacement (every load and prescribed value is zero)");
  // Prescribed values of the collocation constraints, times lambda like the loads.
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const auto& c = constraints_[k];
    if (essential_ == "lagrange") {
      P_[ndof_ + static_cast<Index>(k)] = c.value;
    } else {
      for (size_t a = 0; a < c.sh.nodes.size(); ++a) P_[2 * c.sh.nodes[a] + c.comp] += penalty_ * c.sh.N[a] * c.value;
    }
  }
}

void EfgModel::read_control(Params b) {
  Params c = b.at("control");
  c.validate(kEfgControlKeys);
  const ControlType t =
      PathFollowing::parse(c.choice("type", {"load", "displacement", "generalized_displacement", "arc_length"}));
  control_u_form_ = c.choice("form", {"U", "V"}) == "U";
  double inc = c.number("increment");
  if (inc == 0.0) {
    if (t != ControlType::load)
      c.fail("increment", "required for this control (initial load factor or displacement increment)");
    inc = ctx_.analysis.dt;  // load control by default follows the driver's load factor (time)
  }
  // The body's size (the diagonal of its nodes' bounding box): the scale of a displacement that no step of a
  // geometrically linear analysis may reach (check_runaway()).
  Vec2 lo = mesh_.nodes.front(), hi = lo;
  for (const Vec2& p : mesh_.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  body_size_ = (hi - lo).norm();
  if (t == ControlType::displacement && std::abs(inc) >= body_size_) {
    char m[256];
    std::snprintf(m, sizeof m,
                  "a displacement increment of %.6g, not less than the body's size %.6g (a geometrically linear "
                  "analysis): give a fraction of the expected displacement",
                  std::abs(inc), body_size_);
    c.fail("increment", m);
  }
  if (t == ControlType::displacement) {
    Json sel = {{"type", "point"}, {"at", c.json()["at"]}};
    Params sp(sel, c.file(), c.path());
    const Index n = select_nodes(sp, mesh_.nodes).front();
    control_dof_ = 2 * n + (c.choice("component", {"x", "y"}) == "x" ? 0 : 1);
    if (std::find(fixed_dofs_.begin(), fixed_dofs_.end(), control_dof_) != fixed_dofs_.end())
      c.fail("at", "the controlled dof is held by a boundary condition");
  }
  const ComplexRoots cr =
      PathFollowing::parse_complex_roots(c.choice("complex_roots", {"real_part", "normal_plane", "cut_back"}));
  control_ = PathFollowing(t, inc, control_dof_, cr);
  control_.locate(c.path());
}

}  // namespace lagfsi::efg
