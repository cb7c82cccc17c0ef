// Reading an MPM body from the case file (src/mpm/include/lagfsi/mpm/mpm_model.hpp): the MpmModel constructor. The keys
// are read in this order, so that the first bad one is the one reported: material, grid, options, damping,
// particles of the regions, initial velocity, state and stress, two-phase properties, loads, grid boundary
// conditions, the time scheme (with the explicit step's cost check), absorbing and free-field boundaries.
#include "mpm_body.hpp"
#include "mpm_output.hpp"
#include "mpm_scheme.hpp"

#include <lagfsi/mpm/mpm_model.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lagfsi::mpm {

namespace {

const KeyTable kMpmKeys(
    "/bodies/* (type mpm)",
    "A material point method body: particles carried on a fixed background grid (explicit or implicit).",
    {{"name", nullptr, "Body name (output files <name>.pvd, <name>/*.vtu; probes refer to it)."},
     {"type", "mpm", "`mpm`."},
     {"material", nullptr, "The material (see /bodies/*/material (mpm body, type linear_elastic) and others)."},
     {"grid", nullptr, "The background grid (see /bodies/*/grid (mpm body))."},
     {"regions", nullptr, "Regions filled with particles (see /bodies/*/regions/* (mpm body, ...))."},
     {"particles_per_cell", 2, "Particles per cell in each direction, 1-8."},
     {"shape_functions", "linear", "linear or gimp."},
     {"update", "musl", "Stress update of the explicit scheme: musl, usl or usf."},
     {"cfl", 0.5, "Courant number of the explicit substeps, in (0, 1]."},
     {"flip", 1.0, "FLIP share of the particle velocity update, in [0, 1] (1: FLIP, 0: PIC)."},
     {"boundary_conditions", Json::array(),
      "Grid-node conditions (see /bodies/*/boundary_conditions/* (mpm body, ...))."},
     {"damping", Json::object(), "Damping (see /bodies/*/damping (mpm body))."},
     {"initial_velocity", Json::array({0.0, 0.0}), "Initial velocity [vx, vy] (m/s) of the particles."},
     {"initial_state", Json{{"type", "given"}},
      "Initial velocity field (see /bodies/*/initial_state (mpm body, ...))."},
     {"initial_stress", Json{{"type", "zero"}}, "Initial stress (see /bodies/*/initial_stress (mpm body, ...))."},
     {"particles_csv", false, "Also write the particles as CSV files."},
     {"grid_output", false,
      "Also write <name>_grid.pvd: the grid nodes with mass, velocity, force and boundary flags."},
     {"two_phase", Json::object(), "Saturated soil (see /bodies/*/two_phase (mpm body)); {}: single phase."},
     {"absorbing_boundaries", Json::array(), "Absorbing boundaries (see /bodies/*/absorbing_boundaries/* (mpm body))."},
     {"time_integration", "explicit",
      "explicit, or implicit (the analysis' Newmark or generalized-alpha; linear elastic, single phase, undamped)."},
     {"loads", Json::array(), "Particle loads (see /bodies/*/loads/* (mpm body, type particle_force))."},
     {"gravity", true, "Whether the case's gravity acts on the body."}});

const KeyTable kMpmGridKeys("/bodies/*/grid (mpm body)", "The background grid: square cells over a rectangle.",
                            {{"origin", Json::array({0.0, 0.0}), "Lower-left corner [x, y] (m)."},
                             {"size", nullptr, "Width and height [w, h] (m), a whole number of cells each."},
                             {"cell", nullptr, "Cell size h (m)."}});

const KeyTable kMpmRectangleKeys("/bodies/*/regions/* (mpm body, type rectangle)", "A rectangle inside the grid.",
                                 {{"type", "rectangle", "`rectangle`."},
                                  {"origin", Json::array({0.0, 0.0}), "Lower-left corner [x, y] (m)."},
                                  {"size", nullptr, "Width and height [w, h] (m)."}});

const KeyTable kMpmPolygonKeys("/bodies/*/regions/* (mpm body, type polygon)", "A polygon inside the grid.",
                               {{"type", "polygon", "`polygon`."},
                                {"points", nullptr, "Outline [[x, y], ...] (m), at least 3 points."}});

const KeyTable kMpmPulseKeys("/bodies/*/initial_state (mpm body, type pulse)",
                             "v = amplitude exp(-((x - centre) / width)^2) along an axis (a wave packet).",
                             {{"type", "pulse", "`pulse`."},
                              {"amplitude", nullptr, "Amplitude (m/s)."},
                              {"centre", nullptr, "Centre (m) on the axis."},
                              {"width", nullptr, "Width (m), positive."},
                              {"axis", "x", "x or y."}});

const KeyTable kMpmAxialModeKeys("/bodies/*/initial_state (mpm body, type axial_mode)",
                                 "v = amplitude sin(wavenumber (x - start)) along an axis (a vibrating bar).",
                                 {{"type", "axial_mode", "`axial_mode`."},
                                  {"amplitude", nullptr, "Amplitude (m/s)."},
                                  {"wavenumber", nullptr, "Wavenumber (1/m)."},
                                  {"start", 0.0, "Origin (m) of the sine on the axis."},
                                  {"axis", "x", "x or y."}});

const KeyTable kMpmGivenKeys("/bodies/*/initial_state (mpm body, type given)", "The uniform initial_velocity.",
                             {{"type", "given", "`given`."}});

const KeyTable kMpmGeostaticKeys("/bodies/*/initial_stress (mpm body, type geostatic)",
                                 "Vertical stress from the weight above the surface, horizontal k0 times it.",
                                 {{"type", "geostatic", "`geostatic`."},
                                  {"surface", nullptr, "Height (m) of the ground surface."},
                                  {"k0", 0.0, "Lateral stress ratio; default: poisson / (1 - poisson).", kDerived}});

const KeyTable kMpmZeroStressKeys("/bodies/*/initial_stress (mpm body, type zero)", "No initial stress.",
                                  {{"type", "zero", "`zero`."}});

const KeyTable kMpmTwoPhaseKeys(
    "/bodies/*/two_phase (mpm body)",
    "Saturated soil: the particles carry water (the material's density is then the grains').",
    {{"porosity", nullptr, "Porosity, in (0, 1)."},
     {"water_density", 1000.0, "Water density (kg/m^3)."},
     {"water_bulk_modulus", 2.2e9, "Water bulk modulus (Pa)."},
     {"hydraulic_conductivity", nullptr, "Hydraulic conductivity (m/s)."},
     {"initial_pore_pressure", Json{{"type", "zero"}},
      "Initial pore pressure (see /bodies/*/two_phase/initial_pore_pressure (mpm body, ...))."}});

const KeyTable kMpmPoreHydrostaticKeys("/bodies/*/two_phase/initial_pore_pressure (mpm body, type hydrostatic)",
                                       "Hydrostatic pore pressure below a water level.",
                                       {{"type", "hydrostatic", "`hydrostatic`."},
                                        {"level", nullptr, "Height (m) of the water table."}});

const KeyTable kMpmPoreZeroKeys("/bodies/*/two_phase/initial_pore_pressure (mpm body, type zero)",
                                "No initial pore pressure.", {{"type", "zero", "`zero`."}});

const KeyTable kMpmDampingKeys("/bodies/*/damping (mpm body)",
                               "Cundall's local damping until a time, and Rayleigh damping mass M + stiffness K.",
                               {{"local", 0.0, "Local damping coefficient, in [0, 1)."},
                                {"local_until", 1e30, "Time (s) until which the local damping acts."},
                                {"mass", 0.0, "Mass-proportional Rayleigh coefficient (1/s)."},
                                {"stiffness", 0.0, "Stiffness-proportional Rayleigh coefficient (s)."}});

bool inside_polygon(const std::vector<Vec2>& poly, const Vec2& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

/// "grid": origin, size (a whole number of cells per direction) and cell.
void read_grid(Params g, Grid& grid) {
  g.validate(kMpmGridKeys);
  grid.origin = g.vec2("origin");
  const Vec2 size = g.vec2("size");
  grid.h = g.positive("cell");
  const double h = grid.h;
  if (!(size.x() > 0 && size.y() > 0)) g.fail("size", "must be positive");
  // Cell counts in double until checked (size / cell may be far beyond int's range). A grid costs about
  // 200 bytes per cell (nodal fields, per-thread copies): 1e7 cells is 2 GB.
  const double nxd = std::round(size.x() / h), nyd = std::round(size.y() / h);
  if (!(nxd * nyd <= 1e7)) {
    std::ostringstream os;
    os << nxd << " x " << nyd << " cells (size / cell): more than 1e7, about 200 bytes each";
    g.fail(os.str());
  }
  grid.nx = static_cast<int>(nxd);
  grid.ny = static_cast<int>(nyd);
  if (grid.nx < 1 || grid.ny < 1 || std::abs(grid.nx * h - size.x()) > 1e-9 * size.x() ||
      std::abs(grid.ny * h - size.y()) > 1e-9 * size.y())
    g.fail("cell", "the grid size must be a whole number of cells in each direction");
}

/// Particles: n x n per cell, at the centres of the sub-cells that lie in a region.
void fill_regions(Params regions, const Grid& grid, int ppc, double rho, Particles& P) {
  if (regions.size() == 0) regions.fail("at least one region is needed");
  const double hp = grid.h / ppc;
  std::vector<char> taken(static_cast<size_t>(grid.nx) * grid.ny * ppc * ppc, 0);
  for (size_t r = 0; r < regions.size(); ++r) {
    Params reg = regions.at(r);
    if (!reg.has("type")) reg.fail("type", "required key is missing");
    std::vector<Vec2> poly;
    if (reg.choice("type", {"rectangle", "polygon"}) == "rectangle") {
      reg.validate(kMpmRectangleKeys);
      const Vec2 o = reg.vec2("origin"), s = reg.vec2("size");
      if (!(s.x() > 0 && s.y() > 0)) reg.fail("size", "must be positive");
      poly = {o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())};
    } else {
      reg.validate(kMpmPolygonKeys);
      poly = reg.points("points");
      if (poly.size() < 3) reg.fail("points", "a polygon needs at least 3 points");
    }
    // A region partly outside the grid would be cut silently: an error naming the corner outside.
    const Vec2 lo = grid.origin, hi = grid.origin + grid.h * Vec2(grid.nx, grid.ny), tol = 1e-9 * (hi - lo);
    for (size_t c = 0; c < poly.size(); ++c)
      if ((poly[c].array() < (lo - tol).array()).any() || (poly[c].array() > (hi + tol).array()).any()) {
        std::ostringstream os;
        os << "reaches (" << poly[c].x() << ", " << poly[c].y() << "), outside the grid (" << lo.x() << ".." << hi.x()
           << " x " << lo.y() << ".." << hi.y() << "): the region would be cut";
        reg.fail(reg.string("type") == "rectangle" ? (c == 0 ? "origin" : "size") : "points/" + std::to_string(c),
                 os.str());
      }
    const size_t before = P.size();
    for (int j = 0; j < grid.ny * ppc; ++j)
      for (int i = 0; i < grid.nx * ppc; ++i) {
        const size_t k = static_cast<size_t>(j) * grid.nx * ppc + i;
        const Vec2 q = grid.origin + Vec2((i + 0.5) * hp, (j + 0.5) * hp);
        if (taken[k] || !inside_polygon(poly, q)) continue;
        taken[k] = 1;
        P.add(q, rho * hp * hp, hp * hp);
      }
    if (P.size() == before) reg.fail("the region holds no particle of the grid (is it inside the grid?)");
  }
}

/// Initial velocity: uniform, or an axial mode v = amplitude sin(k (x - x0)) along an axis (the vibrating bar),
/// or a pulse.
void read_initial_state(const Vec2& v0, Params is, Particles& P) {
  for (auto& v : P.v) v = v0;
  if (!is.has("type")) is.fail("type", "required key is missing");
  const std::string ist = is.choice("type", {"given", "axial_mode", "pulse"});
  if (ist == "pulse") {
    // v = amplitude exp(-((x - centre) / width)^2) along an axis (a wave packet for boundary tests).
    is.validate(kMpmPulseKeys);
    const int ax = is.choice("axis", {"x", "y"}) == "x" ? 0 : 1;
    const double A = is.number("amplitude"), x0 = is.number("centre"), w = is.positive("width");
    for (size_t q = 0; q < P.size(); ++q) {
      const double r = (P.x[q][ax] - x0) / w;
      P.v[q] = Vec2::Zero();
      P.v[q][ax] = A * std::exp(-r * r);
    }
  } else if (ist == "axial_mode") {
    is.validate(kMpmAxialModeKeys);
    const int ax = is.choice("axis", {"x", "y"}) == "x" ? 0 : 1;
    const double A = is.number("amplitude"), k = is.number("wavenumber"), x0 = is.number("start");
    for (size_t p = 0; p < P.size(); ++p) {
      P.v[p] = Vec2::Zero();
      P.v[p][ax] = A * std::sin(k * (P.x[p][ax] - x0));
    }
  } else {
    is.validate(kMpmGivenKeys);
  }
}

/// Initial stress: geostatic (vertical stress from the weight above, horizontal K0 times it) or zero; returns
/// the K0 (nu / (1 - nu) unless given).
double read_initial_stress(Params st, const MpmMaterial& mat, double gy, Particles& P) {
  const double nu = mat.poisson(), rho = mat.density();
  if (!st.has("type")) st.fail("type", "required key is missing");
  if (st.choice("type", {"zero", "geostatic"}) == "geostatic") {
    st.validate(kMpmGeostaticKeys, {{"k0", nu / (1 - nu)}});
    const double top = st.number("surface"), k0 = st.non_negative("k0");
    for (size_t p = 0; p < P.size(); ++p) {
      const double sv = rho * gy * (top - P.x[p].y());  // negative (compression) below the surface
      P.stress[p] = {k0 * sv, sv, 0.0, k0 * sv};
    }
    return k0;
  }
  st.validate(kMpmZeroStressKeys);
  return nu / (1 - nu);
}

/// Saturated soil: the material's density is the grains'; the particle carries water (porosity n).
void read_two_phase(Params tp, bool musl, double gy, MpmBody& body) {
  tp.validate(kMpmTwoPhaseKeys);
  body.two_phase = true;
  const double n0 = tp.number("porosity");
  if (!(n0 > 0 && n0 < 1)) tp.fail("porosity", "must lie in (0, 1)");
  WaterProperties& w = body.water;
  w.density = tp.positive("water_density");
  w.bulk_modulus = tp.positive("water_bulk_modulus");
  w.conductivity = tp.positive("hydraulic_conductivity");
  if (body.material->plastic() || !musl)
    tp.fail("two-phase bodies are linear elastic with the MUSL update in this version");
  Params ip = tp.at("initial_pore_pressure");
  if (!ip.has("type")) ip.fail("type", "required key is missing");
  double level = 0;
  const bool hydro = ip.choice("type", {"zero", "hydrostatic"}) == "hydrostatic";
  if (hydro) {
    ip.validate(kMpmPoreHydrostaticKeys);
    level = ip.number("level");
  } else {
    ip.validate(kMpmPoreZeroKeys);
  }
  Particles& P = body.particles;
  const double rho = body.material->density();
  for (size_t q = 0; q < P.size(); ++q) {
    P.porosity[q] = n0;
    P.mass[q] = ((1 - n0) * rho + n0 * w.density) * P.volume0[q];  // saturated mass (probes, energy)
    // Tension positive: a hydrostatic pressure is negative below the level.
    if (hydro) P.pore_pressure[q] = std::min(0.0, w.density * gy * (level - P.x[q].y()));
  }
}

/// What the explicit sub-step dt (at most cfl h / c) cannot follow, each an error naming its key: an initial
/// velocity that carries a particle across more than a cell in one sub-step (the transfers only see the cells
/// next to its own), a gravity that does so from rest (|g| dt^2 > h), a mass-proportional damping whose explicit
/// update v (1 - alpha dt) diverges (alpha dt > 2), an initial stress above the P-wave modulus rho c^2 (a
/// strain above 1) or not finite.
void check_initial_state(Params b, const MpmBody& B, double dt, const CaseContext& ctx) {
  const Grid& grid = B.grid;
  const Particles& P = B.particles;
  auto text = [](double v) {
    std::ostringstream o;
    o << v;
    return o.str();
  };
  double v_max = 0, s_max = 0;
  for (size_t q = 0; q < P.size(); ++q) {
    v_max = std::max(v_max, P.v[q].norm());
    for (double s : P.stress[q]) s_max = std::max(s_max, std::abs(s));
    if (!std::isfinite(P.v[q].norm())) v_max = P.v[q].norm();
    if (!std::isfinite(P.stress[q][0] + P.stress[q][1] + P.stress[q][2] + P.stress[q][3])) s_max = INFINITY;
  }
  if (!(v_max * dt <= grid.h))
    b.fail(b.at("initial_state").string("type") == "given" ? "initial_velocity" : "initial_state",
           "particles at up to " + text(v_max) + " m/s cross more than a cell (" + text(grid.h) +
               " m) in one sub-step of " + text(dt) + " s");
  const double g = std::hypot(B.gravity().x(), B.gravity().y());
  if (!(g * dt * dt <= grid.h))
    Params(Json::array({B.case_gravity.x(), B.case_gravity.y()}), ctx.case_file.string(), "/gravity")
        .fail("|g| = " + text(g) + " m/s^2 carries a particle across more than a cell of body '" + B.name + "' (" +
              text(grid.h) + " m) in one sub-step of " + text(dt) + " s");
  if (!(B.damping.mass * dt <= 2))
    b.at("damping").fail("mass", "alpha dt = " + text(B.damping.mass * dt) + " for the sub-step of " + text(dt) +
                                     " s: above 2 the explicit damping v (1 - alpha dt) diverges");
  const double modulus = B.material->density() * B.material->p_wave_speed() * B.material->p_wave_speed();
  if (!(s_max <= modulus))
    b.fail("initial_stress", "an initial stress of " + text(s_max) +
                                 " Pa, above the P-wave modulus rho c^2 = " + text(modulus) + " Pa (a strain above 1)");
}

/// The explicit scheme of a body ("update" for a single-phase one); a stiff, light or nearly water-filled body
/// could ask for billions of sub-steps cfl h / c (mpm_scheme.cpp) and the run would look hung: an error.
std::unique_ptr<MpmScheme> read_explicit_scheme(Params b, const std::string& update, const MpmBody& B,
                                                const CaseContext& ctx) {
  std::unique_ptr<ExplicitScheme> scheme = B.two_phase ? make_two_phase_scheme()
                                                       : make_explicit_scheme(update == "usl"   ? StressUpdate::Usl
                                                                              : update == "usf" ? StressUpdate::Usf
                                                                                                : StressUpdate::Musl,
                                                                              make_central_difference());
  const Grid& grid = B.grid;
  const double c = scheme->wave_speed(B);
  const double substeps = ctx.analysis.end_time * c / (B.cfl * grid.h);
  // particle and grid-node updates (the grid is cleared and solved every substep); ~0.1-1 us each
  const double work = substeps * (static_cast<double>(B.particles.size()) + (grid.nx + 1.0) * (grid.ny + 1.0));
  if (!(substeps <= 1e8) || !(work <= 1e11)) {
    std::ostringstream os;
    os << "the explicit scheme's stable step cfl h / c (wave speed c = " << c << " m/s, cell " << grid.h << " m) needs "
       << substeps << " substeps over the run (" << work
       << " particle and grid-node updates; the limits are 1e8 and 1e11): check the density, stiffness"
       << (B.two_phase ? ", porosity" : "") << " and cell size";
    b.fail("material", os.str());
  }
  check_initial_state(b, B, std::min(B.cfl * grid.h / c, ctx.analysis.dt), ctx);
  return scheme;
}

/// The implicit scheme: the analysis' Newmark or generalized-alpha, for linear elastic, single-phase, undamped
/// bodies.
std::unique_ptr<MpmScheme> read_implicit_scheme(Params b, const MpmBody& B, const CaseContext& ctx) {
  const Damping& d = B.damping;
  if (B.material->plastic() || B.two_phase || d.local > 0 || d.stiffness > 0 || d.mass > 0)
    b.fail("time_integration", "implicit MPM bodies are linear elastic, single phase and undamped in this version");
  if (!ctx.analysis.integrator.implicit())
    b.fail("time_integration", "an implicit MPM body needs newmark or generalized_alpha");
  return make_implicit_scheme(make_time_integrator(ctx.analysis.integrator), make_linear_solver("cholmod"));
}

}  // namespace

MpmModel::MpmModel(Params b, const CaseContext& ctx) : ctx_(ctx), body_(std::make_unique<MpmBody>()) {
  b.validate(kMpmKeys);
  MpmBody& B = *body_;
  B.name = b.identifier("name");
  B.grid_path = b.child_path("grid");
  B.case_gravity = ctx.gravity;
  if (ctx.analysis.type != "dynamic") b.fail("type", "an MPM body needs a dynamic analysis");
  B.material = make_mpm_material(b.at("material"));
  const MpmMaterial& mat = *B.material;
  Grid& grid = B.grid;
  read_grid(b.at("grid"), grid);
  const int ppc = b.integer("particles_per_cell", 1);
  if (ppc > 8) b.fail("particles_per_cell", "at most 8 per direction");
  B.shape.particles_per_cell = ppc;
  B.shape.gimp = b.choice("shape_functions", {"linear", "gimp"}) == "gimp";
  const std::string update = b.choice("update", {"musl", "usl", "usf"});
  B.cfl = b.positive("cfl");
  B.flip = b.number("flip");
  if (!(B.flip >= 0.0 && B.flip <= 1.0)) b.fail("flip", "must lie in [0, 1] (1: FLIP, 0: PIC)");
  if (B.cfl > 1) b.fail("cfl", "must lie in (0, 1]");
  B.gravity_on = b.boolean("gravity");
  const bool particles_csv = b.boolean("particles_csv");
  const bool grid_output = b.boolean("grid_output");
  Params d = b.at("damping");
  d.validate(kMpmDampingKeys);
  B.damping.local_until = d.number("local_until");
  B.damping.local = d.non_negative("local");
  if (B.damping.local >= 1) d.fail("local", "must lie in [0, 1)");
  B.damping.mass = d.non_negative("mass");
  B.damping.stiffness = d.non_negative("stiffness");

  Particles& P = B.particles;
  fill_regions(b.at("regions"), grid, ppc, mat.density(), P);
  const Vec2 v0 = b.vec2("initial_velocity");
  read_initial_state(v0, b.at("initial_state"), P);
  B.boundaries.k0 = read_initial_stress(b.at("initial_stress"), mat, ctx.gravity.y(), P);
  if (!b.at("two_phase").json().empty()) read_two_phase(b.at("two_phase"), update == "musl", ctx.gravity.y(), B);
  B.loads = read_particle_loads(b.at("loads"), P.X, ctx.base_dir);

  // Grid boundary conditions: fixed components and prescribed motion of the selected grid nodes.
  const std::vector<Vec2> nodes = grid.node_positions();
  read_boundary_conditions(b.at("boundary_conditions"), nodes, B.two_phase, ctx.base_dir, B.boundaries);
  const bool implicit = b.choice("time_integration", {"explicit", "implicit"}) == "implicit";
  scheme_ = implicit ? read_implicit_scheme(b, B, ctx) : read_explicit_scheme(b, update, B, ctx);
  const BoundaryBody bb{grid, P, ppc, mat.density(), B.gravity_on ? ctx.gravity.y() : 0.0, B.two_phase};
  read_absorbing_boundaries(b.at("absorbing_boundaries"), nodes, bb, B.boundaries);
  if (implicit && (!B.boundaries.moving.empty() || !B.boundaries.dashpots.empty()))
    b.fail("time_integration",
           "implicit MPM bodies take fixed nodes only (no prescribed motion or absorbing boundaries) in this version");
  grid.allocate();
  writer_ = std::make_unique<MpmWriter>(ctx.out_dir, particles_csv, grid_output);
}

}  // namespace lagfsi::mpm
