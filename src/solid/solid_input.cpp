// Reading a solid or shell body from the case file (/bodies/i of type "solid" or "shell"): the SolidModel
// constructor (solid_model_impl.hpp): material, geometry and mesh (a shell's mid-line), damping, boundary
// conditions, loads and the initial state.
#include "solid_model_impl.hpp"

#include <algorithm>

namespace lagfsi::solid {

namespace {

/// The keys of solid and shell bodies, then the type's own.
std::vector<KeyDecl> body_keys(const std::string& type, const Json& thickness, std::vector<KeyDecl> own) {
  std::vector<KeyDecl> keys = {
      {"name", nullptr, "Body name (output files <name>.pvd, <name>/*.vtu; probes and couplings refer to it)."},
      {"type", type, "`" + type + "`."},
      {"material", nullptr, "The material (see /bodies/*/material (solid or shell body))."},
      {"thickness", thickness, "Out-of-plane thickness (m)."},
      {"damping", Json::object(), "Rayleigh damping (see /bodies/*/damping (solid or shell body))."},
      {"geometry", nullptr, ""},
      {"mesh", nullptr, ""},
      {"initial_velocity", Json::array({0.0, 0.0}), "Initial velocity [vx, vy] (m/s)."},
      {"boundary_conditions", Json::array(),
       "Supports and prescribed motions (see /bodies/*/boundary_conditions/* (solid body, ...) or (shell body, ...))."},
      {"loads", Json::array(), "Loads (see /bodies/*/loads/* (solid or shell body, ...))."},
      {"gravity", true, "Whether the case's gravity acts on the body."}};
  for (auto& k : own) {
    auto it = std::find_if(keys.begin(), keys.end(), [&](const KeyDecl& d) { return d.name == k.name; });
    if (it != keys.end())
      *it = std::move(k);
    else
      keys.push_back(std::move(k));
  }
  return keys;
}

const KeyTable kSolidKeys("/bodies/* (type solid)",
                          "A 2D continuum (plane strain or stress) of triangles, positional FEM, large displacements.",
                          body_keys("solid", 1.0,
                                    {{"geometry", nullptr,
                                      "The body's shape (see geometry (type rectangle) and others)."},
                                     {"mesh", nullptr, "Its triangles (see mesh (triangles of a geometry))."}}));

const KeyTable kShellKeys(
    "/bodies/* (type shell)", "A positional frame/shell (Reissner kinematics) along a mid-line, SVK law in its frame.",
    body_keys("shell", nullptr,
              {{"geometry", nullptr, "The mid-line (see /bodies/*/geometry (shell body, type line) or polyline)."},
               {"mesh", nullptr, "Elements along the mid-line (see /bodies/*/mesh (shell body))."},
               {"width", 1.0, "Out-of-plane width (m) of the section."},
               {"shear_correction", 5.0 / 6.0, "Shear correction factor."},
               {"shear_integration", "reduced", "reduced (selective reduced integration of shear) or full."}}));

const KeyTable kShellLineKeys("/bodies/*/geometry (shell body, type line)", "A straight mid-line.",
                              {{"type", "line", "`line`."},
                               {"from", nullptr, "One end [x, y] (m)."},
                               {"to", nullptr, "The other end [x, y] (m)."}});

const KeyTable kShellPolylineKeys("/bodies/*/geometry (shell body, type polyline)", "A mid-line of straight segments.",
                                  {{"type", "polyline", "`polyline`."},
                                   {"points", nullptr, "The points [[x, y], ...] (m), at least two."}});

const KeyTable kShellMeshKeys("/bodies/*/mesh (shell body)",
                              "Elements along the mid-line: give either elements (a line) or size.",
                              {{"order", 3, "Element order: 1, 2 or 3."},
                               {"elements", 0, "Number of elements of a line (0: use size)."},
                               {"size", 0.0, "Element length (m); each segment gets ceil(length / size) elements."}});

const KeyTable kMaterialKeys("/bodies/*/material (solid or shell body)", "A hyperelastic material.",
                             {{"type", "svk", "svk (Saint Venant-Kirchhoff) or neo_hookean (solids only)."},
                              {"young", nullptr, "Young's modulus (Pa)."},
                              {"poisson", 0.0, "Poisson's ratio, in (-1, 0.5)."},
                              {"density", nullptr, "Mass density (kg/m^3)."},
                              {"hypothesis", "plane_strain", "plane_strain or plane_stress."}});

const KeyTable kDampingKeys("/bodies/*/damping (solid or shell body)", "Rayleigh damping C = mass M + stiffness K.",
                            {{"mass", 0.0, "Mass-proportional coefficient (1/s), >= 0."},
                             {"stiffness", 0.0, "Stiffness-proportional coefficient (s), >= 0."}});

const char* const kSelectDoc = "The nodes (a shell: mid-line nodes) held (see selection (type point) and others).";
const char* const kComponentsDoc = "Held components: x, y or xy.";
const char* const kValueDoc = "Displacement (m) or velocity (m/s) [x, y], scaled by the function.";
const char* const kFunctionDoc = "Function of time (see time function (type constant) and others).";

const KeyTable kFixedKeys("/bodies/*/boundary_conditions/* (solid body, type fixed)", "Held in place.",
                          {{"type", "fixed", "`fixed`."},
                           {"select", nullptr, kSelectDoc},
                           {"components", "xy", kComponentsDoc}});

const KeyTable kPrescribedKeys("/bodies/*/boundary_conditions/* (solid body, type prescribed_displacement, ...)",
                               "A prescribed displacement or velocity: value times a function of time.",
                               {{"type", nullptr, "prescribed_displacement or prescribed_velocity."},
                                {"select", nullptr, kSelectDoc},
                                {"components", "xy", kComponentsDoc},
                                {"value", nullptr, kValueDoc},
                                {"function", Json{{"type", "constant"}}, kFunctionDoc}});

const KeyTable kShellFixedKeys(
    "/bodies/*/boundary_conditions/* (shell body, type fixed or pinned)",
    "Held in place; pinned is fixed with a free rotation.",
    {{"type", nullptr, "fixed or pinned."},
     {"select", nullptr, kSelectDoc},
     {"components", "xy", kComponentsDoc},
     {"rotation", "fixed", "Whether the section's rotation is held: fixed or free; default: fixed (free when pinned).",
      kDerived}});

const KeyTable kShellPrescribedKeys("/bodies/*/boundary_conditions/* (shell body, type prescribed_displacement, ...)",
                                    "A prescribed displacement or velocity: value times a function of time.",
                                    {{"type", nullptr, "prescribed_displacement or prescribed_velocity."},
                                     {"select", nullptr, kSelectDoc},
                                     {"components", "xy", kComponentsDoc},
                                     {"value", nullptr, kValueDoc},
                                     {"function", Json{{"type", "constant"}}, kFunctionDoc},
                                     {"rotation", "fixed", "Whether the section's rotation is held: fixed or free."}});

const KeyTable kPointLoadKeys(
    "/bodies/*/loads/* (solid or shell body, type point_load or traction)",
    "point_load: a total force split equally over the selected nodes; traction: a force per unit reference area "
    "on the boundary edges whose points are all selected.",
    {{"type", nullptr, "point_load or traction."},
     {"value", nullptr, "Force [x, y] (N), or traction (Pa), scaled by the function."},
     {"select", nullptr, "Where it acts (see selection (type point) and others)."},
     {"function", Json{{"type", "constant"}}, kFunctionDoc}});

const KeyTable kPressureLoadKeys(
    "/bodies/*/loads/* (solid or shell body, type pressure)",
    "A pressure on the boundary edges whose points are all selected (the force is -p n ds, n outward).",
    {{"type", "pressure", "`pressure`."},
     {"value", nullptr, "Pressure (Pa), scaled by the function."},
     {"select", nullptr, "The boundary points (see selection (type point) and others)."},
     {"function", Json{{"type", "constant"}}, kFunctionDoc},
     {"follower", true, "true: follows the deformed boundary; false: acts on the reference one."}});

const KeyTable kBodyForceKeys("/bodies/*/loads/* (solid or shell body, type body_force)",
                              "A force per unit volume on the whole body.",
                              {{"type", "body_force", "`body_force`."},
                               {"value", nullptr, "Force per unit volume [x, y] (N/m^3), scaled by the function."},
                               {"function", Json{{"type", "constant"}}, kFunctionDoc}});

/// The reference mid-line of a shell body: {"type": "line", "from", "to"} or {"type": "polyline",
/// "points"}, cut into elements of the mesh's order by "elements" (a line) or "size" (each segment into
/// ceil(length / size) elements).
std::vector<Vec2> shell_midline(Params geo, Params mesh, int& order) {
  if (!geo.json().is_object() || !geo.has("type")) geo.fail("type", "required key is missing");
  const std::string gt = geo.choice("type", {"line", "polyline"});
  std::vector<Vec2> corners;
  if (gt == "line") {
    geo.validate(kShellLineKeys);
    corners = {geo.vec2("from"), geo.vec2("to")};
  } else {
    geo.validate(kShellPolylineKeys);
    corners = geo.points("points");
    if (corners.size() < 2) geo.fail("points", "a polyline needs at least two points");
  }
  mesh.validate(kShellMeshKeys);
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
  b.validate(shell ? kShellKeys : kSolidKeys);
  name_ = b.identifier("name");

  read_body(b);

  Params damp = b.at("damping");
  damp.validate(kDampingKeys);
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

  read_boundary_conditions(b);

  read_loads(b);

  // Integrator and solver.
  if (!is_static_) {
    integrator_ = make_time_integrator(ctx.analysis.integrator);
  }
  solver_settings_ = ctx.analysis.linear_solver;
  solver_settings_.block_size = static_cast<int>(nd % body_->num_nodes() == 0 ? nd / body_->num_nodes() : 1);
  make_solver();

  state_.t = 0;
  state_.x = body_->reference_positions();
  state_.v = Vec::Zero(nd);
  const Vec2 v0 = b.vec2("initial_velocity");
  for (Index n = 0; n < body_->num_nodes(); ++n) state_.v.segment<2>(2 * n) = v0;
  for (const auto& p : prescribed_) state_.v[p.dof] = 0.0;
  state_.a = Vec::Zero(nd);
  H_ = body_->pattern();
}

void SolidModel::read_body(Params b) {
  const bool shell = type_ == "shell";
  Params mat = b.at("material");
  mat.validate(kMaterialKeys);
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
}

void SolidModel::read_boundary_conditions(Params b) {
  const bool shell = type_ == "shell";
  const auto& stations = body_->stations();
  const Index nd = body_->num_dofs();
  // Boundary conditions: fixed / prescribed displacement / prescribed velocity of the stations'
  // translations; a shell's rotation (its generalised vector) is held by them too unless "rotation" is
  // "free" ("pinned" is "fixed" with a free rotation).
  Params bcs = b.at("boundary_conditions");
  fixed_mask_.assign(nd, 0);
  for (size_t i = 0; i < bcs.size(); ++i) {
    Params bc = bcs.at(i);
    if (!bc.json().is_object() || !bc.has("type")) bc.fail("type", "required key is missing");
    const std::string t = shell
                              ? bc.choice("type", {"fixed", "pinned", "prescribed_displacement", "prescribed_velocity"})
                              : bc.choice("type", {"fixed", "prescribed_displacement", "prescribed_velocity"});
    const bool fixed = t == "fixed" || t == "pinned";
    if (!shell)
      bc.validate(fixed ? kFixedKeys : kPrescribedKeys);
    else if (fixed)
      bc.validate(kShellFixedKeys, {{"rotation", t == "pinned" ? "free" : "fixed"}});
    else
      bc.validate(kShellPrescribedKeys);
    const std::string comps = bc.choice("components", {"x", "y", "xy"});
    const bool hold_rotation = shell && bc.choice("rotation", {"fixed", "free"}) == "fixed";
    const auto sel = select_nodes(bc.at("select"), stations);
    Vec2 value = Vec2::Zero();
    std::shared_ptr<TimeFunction> fn;
    if (t == "prescribed_displacement" || t == "prescribed_velocity") {
      value = bc.vec2("value");
      fn = make_time_function(bc.at("function"), ctx_.base_dir);
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
    bcs.fail(
        "a static analysis needs boundary conditions that hold the body (at least 3 fixed components; "
        "this body has " +
        std::to_string(held) + ")");
}

void SolidModel::read_loads(Params b) {
  const auto& stations = body_->stations();
  const Index nd = body_->num_dofs();
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
    l.validate(t == "pressure" ? kPressureLoadKeys : t == "body_force" ? kBodyForceKeys : kPointLoadKeys);
    Load load{Vec::Zero(nd), std::shared_ptr<TimeFunction>(make_time_function(l.at("function"), ctx_.base_dir)), {}};
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
  if (b.boolean("gravity") && ctx_.gravity.squaredNorm() > 0)
    loads_.push_back({body_->body_force(body_->density() * ctx_.gravity), constant_function(1.0), {}});
}

}  // namespace lagfsi::solid
