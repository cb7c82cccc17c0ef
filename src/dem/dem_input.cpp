// Reading a DEM body from the case file (src/dem/include/lagfsi/dem/dem_model.hpp). Keys and defaults:
//   "name", "type": "dem",
//   "material": {"density" (required), "young": 0, "poisson": 0.3}    (young: Hertz-Mindlin only)
//   "mass": "disc" | "sphere"      m = rho pi r^2 (unit depth), I = m r^2/2 | m = 4/3 rho pi r^3, I = 2/5 m r^2
//   "rotation": true               integrate theta (false: 1/I = 0)
//   "contact": {"law": ...}        dem_contact_law.hpp
//   "discs": [generators]          dem_particles.hpp
//   "walls": [polylines]           dem_walls.hpp
//   "time_step": {"dt": 0 (auto), "fraction": 0.2, "allow_above_critical": false}   (allowed above: a warning)
//   "neighbour": {"skin": 0 (auto: 0.5 r_max), "reorder": true}
//   "overlap_tolerance": 1e-3      initial overlaps above this fraction of the smaller radius are errors; in
//                                  [0, 1); overlaps accepted above 1e-3 are a warning
//   "blast": {}                    dem_blast.hpp (empty: none)
//   "discs_csv": false             also write <name>_discs.csv at each output
//   "crater": {}                   {"surface": 0 (top of the bed at t = 0, after settling), "bin": 0 (2 d_max),
//   "centre": x (default the
//                                  charge's x), "offsets": [-0.05, 0, 0.05]}: crater.csv at each output (empty: none)
//   "settle": {}                   {"time": T, "remove_walls": [names]}: settle under gravity for T before t = 0,
//                                  then remove those walls and start from rest (empty: none)
#include "dem_body.hpp"

#include <lagfsi/dem/dem_model.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace lagfsi::dem {

namespace {

const KeyTable kDemKeys(
    "/bodies/* (type dem)",
    "A discrete element body: rigid discs with contact laws, rigid walls, gravity and an optional air blast.",
    {{"name", "dem", "Body name (output files; probes refer to it)."},
     {"type", "dem", "`dem`."},
     {"material", nullptr, "The discs' material (see /bodies/*/material (dem body))."},
     {"mass", "disc",
      "disc (m = rho pi r^2 per m of depth, I = m r^2 / 2) or sphere (m = 4/3 rho pi r^3, I = 2/5 m r^2)."},
     {"rotation", true, "Integrate the discs' rotation (false: no rotation)."},
     {"contact", nullptr, "The contact law (see /bodies/*/contact (dem body, law linear) and others)."},
     {"discs", nullptr, "Disc generators, appended in order (see /bodies/*/discs/* (dem body, ...))."},
     {"walls", Json::array(), "Rigid walls (see /bodies/*/walls/* (dem body))."},
     {"time_step", Json::object(), "The body's own time step (see /bodies/*/time_step (dem body))."},
     {"neighbour", Json::object(), "Neighbour search (see /bodies/*/neighbour (dem body))."},
     {"overlap_tolerance", 1e-3,
      "Initial overlaps above this fraction of the smaller radius are errors, in [0, 1); accepted ones above 1e-3 "
      "are warnings."},
     {"blast", Json::object(), "An air-blast load (see /bodies/*/blast (dem body)); {}: none."},
     {"settle", Json::object(), "A settling stage before t = 0 (see /bodies/*/settle (dem body)); {}: none."},
     {"discs_csv", false, "Also write <name>_discs.csv at each output."},
     {"crater", Json::object(), "Write crater.csv at each output (see /bodies/*/crater (dem body)); {}: none."}});

const KeyTable kDemMaterialKeys("/bodies/*/material (dem body)", "The discs' material.",
                                {{"density", nullptr, "Mass density (kg/m^3)."},
                                 {"young", 0.0, "Young's modulus (Pa); for the hertz_mindlin law."},
                                 {"poisson", 0.3, "Poisson's ratio, in (-1, 0.5)."}});

const KeyTable kDemTimeStepKeys(
    "/bodies/*/time_step (dem body)",
    "The driver's step is split into sub-steps no longer than this dt (explicit central difference).",
    {{"dt", 0.0, "Sub-step (s); 0: fraction times the critical step 2 / omega_max of the contact law."},
     {"fraction", 0.2, "Fraction of the critical step, in (0, 1]."},
     {"allow_above_critical", false, "Accept a dt above the critical step."}});

const KeyTable kDemNeighbourKeys("/bodies/*/neighbour (dem body)", "The neighbour lists of the contact search.",
                                 {{"skin", 0.0, "Verlet skin (m); 0: half the largest radius."},
                                  {"reorder", true, "Reorder the discs along the grid for memory locality."}});

const KeyTable kDemCraterKeys(
    "/bodies/*/crater (dem body)", "The crater profile of a blast, written to crater.csv at each output.",
    {{"surface", 0.0, "Ground level (m); 0: the top of the bed at t = 0, after any settling."},
     {"bin", 0.0, "Width (m) of the profile's bins; 0: twice the largest diameter."},
     {"centre", 0.0, "x (m) of the crater's centre; default: the charge's x (0 without a blast).", kDerived},
     {"offsets", Json::array({-0.05, 0.0, 0.05}), "Offsets (m) from the centre where the depth is read."}});

const KeyTable kDemSettleKeys("/bodies/*/settle (dem body)",
                              "Settle under gravity before t = 0, then remove walls and start from rest.",
                              {{"time", nullptr, "Settling time (s)."},
                               {"remove_walls", Json::array(), "Names of the walls removed after it."}});

}  // namespace

namespace {

constexpr double kDefaultOverlapTolerance = 1e-3;

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

/// Initial overlaps between discs, and between discs and walls, above tol x the smaller radius; coincident
/// discs (no contact normal) whatever tol. Keeps the largest overlap accepted (b.initial_overlap, / radius).
void check_overlaps(Params body, DemBody& b, double tol) {
  const Index n = static_cast<Index>(b.size());
  NeighbourGrid g;
  g.bin(b.state.x.data(), 3, n, 2 * b.r_max);
  PairList l;
  g.build(b.state.x.data(), 3, b.discs.radius.data(), n, 0.0, l);
  for (size_t k = 0; k < l.size(); ++k) {
    const Index i = std::min(l.i[k], l.j[k]), j = std::max(l.i[k], l.j[k]);
    const double d = (b.position(i) - b.position(j)).norm();
    const double ov = b.discs.radius[i] + b.discs.radius[j] - d;
    if (!(d > 1e-9 * b.r_min))
      body.at("discs")
          .at(b.discs.group[j])
          .fail("discs " + std::to_string(i) + " and " + std::to_string(j) + " coincide at (" + fmt(b.position(i).x()) +
                ", " + fmt(b.position(i).y()) + "): no contact normal between them");
    const double rmin = std::min(b.discs.radius[i], b.discs.radius[j]);
    b.initial_overlap = std::max(b.initial_overlap, ov / rmin);
    if (ov > tol * rmin)
      body.at("discs")
          .at(b.discs.group[j])
          .fail("discs " + std::to_string(i) + " at (" + fmt(b.position(i).x()) + ", " + fmt(b.position(i).y()) +
                ") and " + std::to_string(j) + " at (" + fmt(b.position(j).x()) + ", " + fmt(b.position(j).y()) +
                ") overlap by " + fmt(ov) + " m, more than overlap_tolerance (" + fmt(tol) +
                ") times the smaller radius");
  }
  for (Index p = 0; p < n; ++p)
    for (size_t w = 0; w < b.walls.size(); ++w)
      for (size_t s = 0; s < b.walls[w].segments(); ++s) {
        const Vec2 c = b.position(p);
        const double ov = b.discs.radius[p] - (closest_on_segment(b.walls[w].a(s), b.walls[w].b(s), c) - c).norm();
        b.initial_overlap = std::max(b.initial_overlap, ov / b.discs.radius[p]);
        if (ov > tol * b.discs.radius[p])
          body.at("walls").at(w).fail("disc " + std::to_string(p) + " at (" + fmt(c.x()) + ", " + fmt(c.y()) +
                                      ") overlaps this wall by " + fmt(ov) + " m");
      }
}

/// /bodies/i/time_step: the sub-step from the contact law's critical step, with the checks that name what is at
/// fault (an overflowing law, a step above the critical one, a run too long, a gravity the sub-step cannot follow).
void read_time_step(Params body, const CaseContext& ctx, DemBody& b) {
  const Discs& D = b.discs;
  const Index n = static_cast<Index>(D.mass.size());
  Params ts = body.at("time_step");
  ts.validate(kDemTimeStepKeys);
  double m_min = D.mass[0];
  for (double m : D.mass) m_min = std::min(m_min, m);
  const double omega = b.law->max_frequency(m_min, b.r_min, b.inertia_factor, b.rotation);
  b.dt_critical = 2.0 / omega;
  // An overflow or underflow in the law's stiffness, the density or the radius, not the step, is then at fault.
  if (!(b.dt_critical > 0 && std::isfinite(b.dt_critical)))
    body.fail("contact", "the contact law's highest frequency omega_max = " + fmt(omega) +
                             " rad/s for the lightest disc (m = " + fmt(m_min) + " kg, r = " + fmt(b.r_min) +
                             " m) is not a finite positive number: check the stiffness, density and radii");
  const double dt = ts.non_negative("dt"), fraction = ts.positive("fraction");
  if (fraction > 1) ts.fail("fraction", "must lie in (0, 1]");
  b.dt = dt > 0 ? dt : fraction * b.dt_critical;
  if (b.dt > b.dt_critical) {
    if (!ts.boolean("allow_above_critical"))
      ts.fail("dt", "dt = " + fmt(b.dt) + " s is above the critical step 2/omega_max = " + fmt(b.dt_critical) +
                        " s of the contact law (set allow_above_critical to force it)");
    // The sub-steps are no longer than the driver's step either (DemModel::solve_iteration).
    const double h = std::min(b.dt, ctx.analysis.dt);
    if (h > b.dt_critical)
      b.warnings.push_back(ts.child_path("dt") + ": sub-steps of " + fmt(h) + " s, above the critical step " +
                           fmt(b.dt_critical) +
                           " s (allow_above_critical): the central difference is unstable "
                           "there, and a run whose energy grows past the work put in stops");
  }
  const double steps = ctx.analysis.end_time / std::min(b.dt, ctx.analysis.dt);
  if (!(steps * n <= 2e13))
    ts.fail("dt", "the run needs " + fmt(steps) + " sub-steps of " + fmt(std::min(b.dt, ctx.analysis.dt)) + " s for " +
                      std::to_string(n) +
                      " discs, more than 2e13 disc updates (the critical step of the contact "
                      "law is " +
                      fmt(b.dt_critical) + " s): a shorter end_time, fewer or larger discs, or softer contacts");
  // Gravity alone moving a disc by a sizeable share of its radius in one sub-step (g h^2) is more than the
  // contacts can resolve.
  const double h_max = std::min(ctx.analysis.dt, b.dt);
  const double g = std::hypot(b.gravity.x(), b.gravity.y());  // no overflow in the squares
  if (!(g * h_max * h_max < 0.1 * b.r_min))
    Params(Json::array({b.gravity.x(), b.gravity.y()}), ctx.case_file.string(), "/gravity")
        .fail("|g| = " + fmt(g) + " m/s^2 moves a disc by g h^2 = " + fmt(g * h_max * h_max) +
              " m in one sub-step of " + fmt(h_max) + " s, more than a tenth of the smallest radius (" + fmt(b.r_min) +
              " m)");
  b.integrator = make_central_difference();
}

}  // namespace

double read_dem_body(Params body, const CaseContext& ctx, DemBody& b) {
  body.validate(kDemKeys);
  b.csv = body.boolean("discs_csv");
  b.name = body.identifier("name");
  b.file = ctx.case_file.string();
  // The discs move in time: a static analysis (load factor 0..1, no inertia) would run a second of dynamics.
  if (ctx.analysis.type != "dynamic")
    body.fail("type", "a DEM body needs a dynamic analysis (analysis.type = \"dynamic\")");
  Params mat = body.at("material");
  mat.validate(kDemMaterialKeys);
  const double rho = mat.positive("density"), young = mat.non_negative("young"), nu = mat.number("poisson");
  if (!(nu > -1 && nu < 0.5)) mat.fail("poisson", "must lie in (-1, 0.5)");
  const bool sphere = body.choice("mass", {"disc", "sphere"}) == "sphere";
  b.rotation = body.boolean("rotation");
  b.inertia_factor = sphere ? 0.4 : 0.5;
  b.law = make_contact_law(body.at("contact"), young, nu, rho);
  b.walls = read_walls(body.at("walls"), ctx.base_dir);
  for (size_t w = 0; w < b.walls.size(); ++w) {
    for (size_t s = 0; s < b.walls[w].segments(); ++s)
      b.segments.emplace_back(static_cast<int>(w), static_cast<int>(s));
    for (size_t v = 0; v < w; ++v)
      if (b.walls[v].name == b.walls[w].name) body.at("walls").at(w).fail("name", "duplicate wall name");
  }
  b.gravity = ctx.gravity;

  // discs
  const auto specs = generate_discs(body.at("discs"), &b.warnings);
  const Index n = static_cast<Index>(specs.size());
  b.state.x.resize(3 * n);
  b.state.v.resize(3 * n);
  b.state.a = Vec::Zero(3 * n);
  b.inv_mass.resize(3 * n);
  Discs& D = b.discs;
  b.r_min = specs[0].r;
  b.r_max = specs[0].r;
  for (Index p = 0; p < n; ++p) {
    const DiscSpec& s = specs[p];
    const double m = sphere ? 4.0 / 3.0 * std::numbers::pi * rho * s.r * s.r * s.r : std::numbers::pi * rho * s.r * s.r;
    // The contacts take products of two masses (m_eff = m_i m_j / (m_i + m_j)) and m r^2: 1e-100..1e100 kg.
    if (!(m > 1e-100 && m < 1e100 && std::isfinite(m * s.r * s.r)))
      body.at("discs").at(s.group).fail("disc " + std::to_string(p) + " of radius " + fmt(s.r) + " m has a mass of " +
                                        fmt(m) + " kg (density " + fmt(rho) +
                                        " kg/m^3): out of the range of 1e-100 to 1e100 kg this code computes with");
    D.radius.push_back(s.r);
    D.mass.push_back(m);
    D.inertia.push_back(b.inertia_factor * m * s.r * s.r);
    D.id.push_back(p);
    D.mark.push_back(0);
    D.group.push_back(s.group);
    if (!std::isfinite(0.5 * m * s.v.squaredNorm() + 0.5 * D.inertia.back() * s.w * s.w))
      body.at("discs").at(s.group).fail("velocity", "the kinetic energy of disc " + std::to_string(p) +
                                                        " (m = " + fmt(m) +
                                                        " kg) overflows: check the velocity and angular_velocity");
    b.state.x.segment<3>(3 * p) << s.x.x(), s.x.y(), 0.0;
    b.state.v.segment<3>(3 * p) << s.v.x(), s.v.y(), s.w;
    b.inv_mass.segment<3>(3 * p) << 1.0 / m, 1.0 / m, b.rotation ? 1.0 / D.inertia.back() : 0.0;
    b.r_min = std::min(b.r_min, s.r);
    b.r_max = std::max(b.r_max, s.r);
  }
  // Coordinates must resolve the radius (x + r must differ from x by about r): at most 1e9 radii from the origin.
  for (size_t w = 0; w < b.walls.size(); ++w)
    for (size_t k = 0; k < b.walls[w].points.size(); ++k)
      if (!(b.walls[w].points[k].cwiseAbs().maxCoeff() < 1e9 * b.r_min))
        body.at("walls").at(w).at("points").at(k).fail("more than 1e9 times the smallest radius (" + fmt(b.r_min) +
                                                       " m) from the origin: the coordinates do not resolve the discs");
  b.where.resize(n);
  for (Index p = 0; p < n; ++p) b.where[p] = p;
  // An overlap of a whole radius puts the disc's centre on the wall line (no contact normal; the smaller disc's
  // centre inside the other one): the contact would push it through.
  const double tol = body.non_negative("overlap_tolerance");
  if (!(tol < 1)) body.fail("overlap_tolerance", "must lie in [0, 1) (a fraction of the smaller radius)");
  check_overlaps(body, b, tol);
  if (b.initial_overlap > kDefaultOverlapTolerance)
    b.warnings.push_back(body.child_path("overlap_tolerance") + ": initial overlaps of up to " +
                         fmt(b.initial_overlap) + " of the radius were accepted (overlap_tolerance " + fmt(tol) +
                         "): their elastic energy is released as motion at the start");

  read_time_step(body, ctx, b);

  Params nb = body.at("neighbour");
  nb.validate(kDemNeighbourKeys);
  b.skin = nb.non_negative("skin");
  if (b.skin == 0) b.skin = 0.5 * b.r_max;
  b.reorder = nb.boolean("reorder");

  Params bl = body.at("blast");
  if (!bl.json().empty()) {
    b.blast.emplace(bl);
    const Vec2 g = b.blast->charge();
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (Index p = 0; p < n; ++p) {
      const Vec2 c = b.position(p);
      const double r = D.radius[p];
      if ((c - g).norm() <= r) bl.fail("position", "the charge lies inside disc " + std::to_string(p));
      xmin = std::min(xmin, c.x() - r);
      xmax = std::max(xmax, c.x() + r);
      ymin = std::min(ymin, c.y() - r);
      ymax = std::max(ymax, c.y() + r);
    }
    if (g.x() >= xmin && g.x() <= xmax && g.y() >= ymin && g.y() <= ymax)
      bl.fail("position", "the charge (" + fmt(g.x()) + ", " + fmt(g.y()) + ") is inside the bed (discs span x " +
                              fmt(xmin) + " .. " + fmt(xmax) + ", y " + fmt(ymin) + " .. " + fmt(ymax) +
                              "): the blast model needs it above the surface");
  }

  Params cr = body.at("crater");
  if (!cr.json().empty()) {
    cr.validate(kDemCraterKeys, {{"centre", b.blast ? b.blast->charge().x() : 0.0}});
    b.crater.enabled = true;
    b.crater.surface = cr.number("surface");  // 0: set at t = 0 (DemModel::initialize), after any settling
    b.crater.bin = cr.non_negative("bin");
    b.crater.centre = cr.number("centre");
    b.crater.offsets = cr.numbers("offsets");
    if (b.crater.offsets.empty()) cr.fail("offsets", "at least one offset");
  }

  Params st = body.at("settle");
  double settle = 0;
  if (!st.json().empty()) {
    st.validate(kDemSettleKeys);
    settle = st.positive("time");
    Params rw = st.at("remove_walls");
    for (size_t i = 0; i < rw.size(); ++i) {
      const auto& v = rw.at(i).json();
      if (!v.is_string() ||
          std::none_of(b.walls.begin(), b.walls.end(), [&](const Wall& w) { return w.name == v.get<std::string>(); }))
        rw.at(i).fail("no wall of that name");
      b.remove_after_settle.push_back(v.get<std::string>());
    }
  }
  return settle;
}

}  // namespace lagfsi::dem
