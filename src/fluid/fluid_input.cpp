// The fluid's input (/bodies/i of type "fluid"): its constants, the scheme and its keys, the walls, the
// particles of the fluid regions (structured or unstructured), the domain box and the initial states.
#include "fluid_defaults.hpp"
#include "fluid_model_impl.hpp"
#include "point_grid.hpp"

#include <lagfsi/linear_solver_input.hpp>
#include <lagfsi/mpi_run.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

namespace lagfsi::fluid {

namespace {

const KeyTable kFluidKeys(
    "/bodies/* (type fluid)",
    "A free-surface Newtonian fluid (PFEM: particles remeshed every step, or a fixed mesh with \"remesh\": false).",
    {{"name", nullptr, "Body name (output files <name>.pvd, <name>/*.vtu; probes refer to it)."},
     {"type", "fluid", "`fluid`."},
     {"density", nullptr, "Mass density (kg/m^3)."},
     {"viscosity", nullptr, "Dynamic viscosity (Pa s), >= 0."},
     {"spacing", nullptr, "Particle spacing h (m): the mesh size; lengths below are often multiples of it."},
     {"preset", "conservative",
      "The family of defaults of the keys marked derived: conservative (the advected domain, walls as constraints "
      "sliding against their Navier friction, the Robin free-surface pressure with the monolithic scheme, particle "
      "volumes; needs remeshing) or classic (the alpha shape, wall particles, p = 0 on the free surface, the surface "
      "correction); default: conservative with the monolithic scheme and remeshing, classic otherwise. A key given "
      "in the case overrides its preset's value.",
      kDerived},
     {"alpha", 1.2, "Alpha-shape parameter in [1, 5]: triangles with a circumradius above alpha h are not fluid."},
     {"domain_detection", "alpha",
      "Which new triangles are fluid: alpha (the alpha shape), advected (the previous domain moved with the "
      "particles) or level_set; default: advected with the monolithic scheme and remeshing, alpha otherwise.",
      kDerived},
     {"separation_alpha", 2.5,
      "Advected/level-set detection: an element inside the domain with an edge beyond this times h is separated "
      "(a film tearing); with walls as constraints, one along a wall only by its other edges (water against a "
      "wall stays); at least alpha."},
     {"level_set_band", 0.25, "Level-set detection: width of the band around the advected boundary, times h."},
     {"contact_gap", 0.0,
      "Fluid parts are joined only once the gap between them is at most this times h (0: off, at most 2); "
      "default: 0.3 with the advected detection, 0 otherwise.",
      kDerived},
     {"keep_edges_angle", 0.0,
      "Hysteresis of the Delaunay flips (degrees, below 90): an edge of the last mesh is kept while the two angles "
      "facing it sum to less than 180 plus this."},
     {"wall_model", "particles",
      "How rigid walls hold the fluid: particles (a layer of fixed particles) or constraints (on the fluid "
      "particles on them); default: constraints with the monolithic scheme, remeshing and a detection other "
      "than alpha, particles otherwise.",
      kDerived},
     {"wall_snap_fraction", 0.1,
      "A particle whose step ends beyond a wall, or within this times h of it while approaching, is put on it "
      "(below 0.5)."},
     {"wall_friction", "held",
      "Walls as constraints: held (their particles do not slide) or navier (sliding against a Navier friction); "
      "default: navier with constraints under the monolithic scheme and remeshing, held otherwise.",
      kDerived},
     {"slip_length", 0.5, "Navier friction: the slip length, times h."},
     {"domain_margin", 0.1,
      "Particles leaving the domain box (walls and initial fluid, enlarged by this times its larger side) are "
      "removed."},
     {"remesh", true, "true: PFEM (remeshed every step); false: the initial mesh for the whole run."},
     {"regions", nullptr, "The fluid's initial regions: geometries (see geometry (type rectangle) and others)."},
     {"particles", "structured",
      "Particles of the regions: structured (a square lattice of spacing h; rectangles only) or unstructured (the "
      "nodes of a Delaunay mesh, its outline split at h, about as dense as a lattice of spacing h)."},
     {"walls", Json::array(), "Rigid walls (see /bodies/*/walls/* (fluid body))."},
     {"boundaries", Json::array(),
      "Boundary conditions on segments of the fluid's boundary, each chosen by its type (see "
      "/bodies/*/boundaries/* (fluid body, type inflow), (type outflow) and (type prescribed_velocity))."},
     {"size_field", Json{{"type", "uniform"}},
      "The particle size: uniform (the spacing everywhere) or adaptive (fine at the surface and walls, coarse in "
      "the bulk; see /bodies/*/size_field (fluid body, type adaptive))."},
     {"initial_velocity", Json::array({0.0, 0.0}), "Initial velocity [vx, vy] (m/s) of the fluid particles."},
     {"initial_pressure", Json{{"type", "zero"}},
      "Initial pressure (see /bodies/*/initial_pressure (fluid body, ...))."},
     {"initial_state", Json{{"type", "given"}},
      "An analytic initial state that overrides initial_velocity and initial_pressure (see "
      "/bodies/*/initial_state (fluid body, ...))."},
     {"scheme", Json::object(),
      "The solution scheme and its settings (see /bodies/*/scheme (fluid body, ...)); default: the monolithic "
      "scheme."}});

/// The scheme keys of both schemes (particles, mass conservation).
std::vector<KeyDecl> scheme_keys(const std::string& type, std::vector<KeyDecl> own) {
  std::vector<KeyDecl> keys = {
      {"type", type, "The scheme: monolithic_pspg (default) or fractional_step; this one is `" + type + "`."},
      {"volume_correction", "none",
       "How the area the remeshing adds or removes is put back: surface, source, particle (advected or level-set "
       "detection, no inflow or outflow) or none; default: surface with the alpha detection, "
       "particle with the monolithic scheme and remeshing (surface with an inflow or outflow), source with an inflow "
       "or outflow otherwise (none behind an inflow that holds a layer), none otherwise.",
       kDerived},
      {"split_edge_factor", 1.6,
       "Advected and level-set detection: free-surface edges longer than this times h are split (0: off, else "
       ">= 1)."},
      {"volume_relaxation_time", 0.1,
       "Time (s) over which the source or particle correction returns the area; default: 0.01 with particle (20 "
       "times the analysis' dt with the fractional step), 0.1 otherwise.",
       kDerived},
      {"remove_close_fraction", 0.3, "Of two particles closer than this times h one is removed (0: off; below 0.9)."},
      {"insert_area_factor", 1.0, "Elements larger than this times h^2 get a particle at their centroid (0: off)."},
      {"bulk_modulus", 2.2e9, "Bulk modulus (Pa) of the weakly compressible continuity (0: incompressible)."},
      {"flat_element_fraction", 0.01, "Elements of area below this times h^2 are removed from the mesh."}};
  for (auto& k : own) keys.push_back(std::move(k));
  return keys;
}

const std::vector<std::string> kPspgDirect{"klu", "umfpack", "eigen_lu", "mumps"};
// "auto": the sizes (unknowns) from which the Krylov solver costs less per run than the direct one, measured on the
// dam break (docs/decisions/0011-krylov-solvers.md): KLU's factorization grows faster than linearly while a
// Krylov solve with multigrid costs about the same per unknown; below, the direct solver's back-solves (several
// a step with one factorization) are cheaper than Krylov solves.
constexpr Index kPspgKrylovFrom = 6000;
constexpr Index kFractionalStepKrylovFrom = 20000;
const std::vector<std::string> kFractionalStepDirect{"cholmod", "cholmod_supernodal", "eigen_ldlt", "mumps"};

const KeyTable kPspgKeys(
    "/bodies/*/scheme (fluid body, type monolithic_pspg)",
    "The monolithic scheme: Newton on positions and pressures with PSPG stabilisation, the analysis' integrator.",
    scheme_keys("monolithic_pspg",
                {{"tau", Json{{"type", "automatic"}},
                  "The stabilisation parameter (see /bodies/*/scheme/tau (fluid body, ...))."},
                 {"mass", "lumped", "Mass matrix: lumped or consistent."},
                 {"free_surface_pressure", "dirichlet",
                  "dirichlet (p = 0 imposed), natural (traction-free in the weak form) or robin (pulled weakly to it); "
                  "default: robin with remeshing and a detection other than alpha (without an inflow or outflow), "
                  "dirichlet otherwise.",
                  kDerived},
                 {"robin_factor", 0.04,
                  "Weight of the Robin free-surface term (a tuned value; 0.01-0.2 keep the area)."},
                 {"tolerance", 1e-4, "Relative tolerance of the Newton iterations."},
                 {"refactorize_every", 0, "Factorize the Newton matrix every this many iterations (0: once a step)."},
                 {"linear_solver", Json{{"type", "auto"}}, linear_solver_doc(kPspgDirect)}}));

const KeyTable kFractionalStepKeys(
    "/bodies/*/scheme (fluid body, type fractional_step)",
    "The fractional step: a predictor, a pressure Poisson solve and a correction per step, p = 0 on the free "
    "surface.",
    scheme_keys("fractional_step",
                {{"viscous_step", "automatic",
                  "automatic (implicit when dt > rho (0.3 h)^2 / (8 mu)), explicit or implicit."},
                 {"linear_solver", Json{{"type", "auto"}}, linear_solver_doc(kFractionalStepDirect)},
                 {"inverted_elements", "retry",
                  "A step in which an element turns over: retry (with dt / 2) or remesh (kept, left to the next "
                  "remesh)."},
                 {"mass", "lumped",
                  "The predictor's mass matrix: lumped or consistent (in the elements off the free surface; not with "
                  "a distributed linear solver)."}}));

const KeyTable kTauAutomaticKeys("/bodies/*/scheme/tau (fluid body, type automatic)",
                                 "PSPG parameter from the element size, the time step and the viscosity.",
                                 {{"type", "automatic", "`automatic`."}});

const KeyTable kTauVelocityKeys("/bodies/*/scheme/tau (fluid body, type velocity_scale)",
                                "PSPG parameter from a given velocity scale.",
                                {{"type", "velocity_scale", "`velocity_scale`."},
                                 {"U", nullptr, "The velocity scale (m/s), positive."}});

const KeyTable kStructuredRegionKeys("/bodies/*/regions/* (fluid body, particles structured)",
                                     "A region of structured particles: a rectangle (each side at least h / 2).",
                                     {{"type", "rectangle", "`rectangle`."},
                                      {"origin", Json::array({0.0, 0.0}), "Lower-left corner [x, y] (m)."},
                                      {"size", nullptr, "Width and height [w, h] (m)."}});

const KeyTable kPressureZeroKeys("/bodies/*/initial_pressure (fluid body, type zero)", "p = 0 everywhere.",
                                 {{"type", "zero", "`zero`."}});

const KeyTable kPressureHydrostaticKeys("/bodies/*/initial_pressure (fluid body, type hydrostatic)",
                                        "p = rho g (level - y) below the level, 0 above.",
                                        {{"type", "hydrostatic", "`hydrostatic`."},
                                         {"level", nullptr, "Height (m) of the free surface."}});

const KeyTable kStateGivenKeys("/bodies/*/initial_state (fluid body, type given)",
                               "initial_velocity and initial_pressure as given.", {{"type", "given", "`given`."}});

const KeyTable kStateTaylorGreenKeys(
    "/bodies/*/initial_state (fluid body, type taylor_green)",
    "Divergence-free cellular flow on a square: u = U sin(pi X) cos(pi Y), v = -U cos(pi X) sin(pi Y).",
    {{"type", "taylor_green", "`taylor_green`."},
     {"amplitude", nullptr, "U (m/s)."},
     {"origin", Json::array({0.0, 0.0}), "Corner [x0, y0] (m) of the square; X = (x - x0) / L."},
     {"length", nullptr, "Side L (m) of the square."}});

const KeyTable kStateSolitaryKeys("/bodies/*/initial_state (fluid body, type solitary_wave)",
                                  "Laitone's first-order solitary wave moving towards +x (needs gravity).",
                                  {{"type", "solitary_wave", "`solitary_wave`."},
                                   {"depth", nullptr, "Still-water depth d (m)."},
                                   {"height", nullptr, "Wave height H (m)."},
                                   {"crest", nullptr, "x (m) of the crest."}});

}  // namespace

FluidModel::FluidModel(Params b, const CaseContext& ctx) : ctx_(ctx) {
  const FluidDefaults d = fluid_defaults(b.json());
  RemeshPipeline::Settings rs;
  read_body_keys(b, d, rs);
  PspgSettings ps;
  FractionalStepSettings fs;
  const bool pspg = read_scheme(b.at("scheme"), d, rs, ps, fs);

  // The analysis' integrator (read for both schemes; the fractional step does not use it).
  if (pspg && !ctx.analysis.integrator.implicit())
    throw InputError(ctx.case_file.string(), "/analysis/integrator/type",
                     "the monolithic fluid scheme is implicit (use newmark or generalized_alpha)");
  std::unique_ptr<TimeIntegrator> integrator = make_time_integrator(ctx.analysis.integrator);
  scheme_ = pspg ? make_pspg_scheme(parts(), ps, std::move(integrator)) : make_fractional_step(parts(), fs);
  build_particles(b);
}

void FluidModel::read_body_keys(Params b, const FluidDefaults& d, RemeshPipeline::Settings& rs) {
  SizeField::expand_shorthand(b.json());
  b.validate(kFluidKeys, {{"preset", d.preset},
                          {"domain_detection", d.detection},
                          {"contact_gap", d.contact_gap},
                          {"wall_model", d.wall_model},
                          {"wall_friction", d.wall_friction}});
  c_.name = b.identifier("name");
  c_.gravity = ctx_.gravity;
  if (ctx_.analysis.type != "dynamic") b.fail("type", "a fluid needs a dynamic analysis");
  c_.rho = b.positive("density");
  c_.mu = b.non_negative("viscosity");
  c_.h = b.positive("spacing");
  rs.alpha = b.positive("alpha");
  if (rs.alpha < 1.0 || rs.alpha > 5.0) b.fail("alpha", "must lie in [1, 5] (the literature uses 1.0-1.5)");
  c_.remesh = b.boolean("remesh");
  if (b.choice("preset", {"conservative", "classic"}) == "conservative" && !c_.remesh)
    b.fail("preset", "\"conservative\" needs \"remesh\": true (its domain and walls act at the remeshing)");
  const std::string detection = b.choice("domain_detection", {"alpha", "advected", "level_set"});
  rs.detection = detection == "alpha"      ? meshing::DomainDetection::Alpha
                 : detection == "advected" ? meshing::DomainDetection::Advected
                                           : meshing::DomainDetection::LevelSet;
  rs.separation_alpha = b.positive("separation_alpha");
  if (rs.separation_alpha < rs.alpha)
    b.fail("separation_alpha", "must be at least alpha (" + std::to_string(rs.alpha) + ")");
  rs.level_set_band = b.non_negative("level_set_band");
  rs.contact_gap = b.non_negative("contact_gap");
  if (rs.contact_gap > 2.0) b.fail("contact_gap", "must be at most 2 (a fraction of the spacing; 0: off)");
  const double keep_deg = b.non_negative("keep_edges_angle");
  if (keep_deg >= 90.0) b.fail("keep_edges_angle", "must be below 90 degrees");
  rs.keep_edges_angle = keep_deg * std::numbers::pi / 180.0;
  rs.domain_margin = b.non_negative("domain_margin");
  // How the rigid walls hold the fluid (fluid_walls.hpp): a layer of fixed particles, or constraints on the
  // fluid particles that lie on them.
  wall_constraints_ = b.choice("wall_model", {"particles", "constraints"}) == "constraints";
  if (wall_constraints_ && !c_.remesh)
    b.fail("wall_model", "\"constraints\" is for PFEM mode (a fixed mesh always constrains its nodes on walls)");
  if (wall_constraints_ && rs.detection == meshing::DomainDetection::Alpha)
    b.fail("wall_model",
           "\"constraints\" needs \"domain_detection\": \"advected\" or \"level_set\" (the alpha "
           "shape's particle removal does not keep particles on walls)");
  // No-slip walls as constraints: their particles held ("held"), or sliding against the Navier friction
  // ("navier"; fluid_walls.hpp).
  const bool navier = b.choice("wall_friction", {"held", "navier"}) == "navier";
  const double slip_length = b.positive("slip_length");
  if (navier && !wall_constraints_)
    b.fail("wall_friction",
           "\"navier\" is for \"wall_model\": \"constraints\" (wall particles hold the fluid by the mesh)");
  c_.wall_snap_fraction = b.non_negative("wall_snap_fraction");
  if (c_.wall_snap_fraction >= 0.5) b.fail("wall_snap_fraction", "must be below 0.5");
  // The walls' model (fluid_walls.hpp); a ceiling lets go of a particle it pulls with more than 1 % of its weight,
  // 0.01 rho |g| h_i^2 (not the noise of a contact line; WallContacts::release_pulled).
  std::unique_ptr<FluidWalls> walls;
  if (!c_.remesh)
    walls = std::make_unique<FixedMeshWalls>();
  else if (wall_constraints_)
    walls = std::make_unique<WallContacts>(c_.h, c_.wall_snap_fraction, c_.gravity, 0.01 * c_.rho * c_.gravity.norm());
  else {
    auto particles = std::make_unique<WallParticles>();
    const WallParticles* solid = particles.get();  // owned by boundaries_, which outlives remesh_'s use of it
    remesh_.set_wall_solid([solid](const Vec2& x, double t) { return solid->solid_depth(x, t).depth; });
    walls = std::move(particles);
  }
  if (navier) walls->set_navier_friction(c_.mu, slip_length);
  boundaries_.set_walls(std::move(walls));
  if (wall_constraints_)
    remesh_.set_wall_lines([this](const Vec2& x) { return boundaries_.along(x); },
                           [this](const Vec2& x) { return boundaries_.along_fixed(x); });
  // The particle size field (size_field.hpp): an adaptive one needs remeshing and graded regions (unstructured
  // particles).
  SizeField size;
  size.read(b, c_.h);
  if (size.adaptive()) {
    if (!c_.remesh) b.at("size_field").fail("type", "\"adaptive\" needs \"remesh\": true");
    if (b.string("particles") != "unstructured")
      b.at("size_field").fail("type", "\"adaptive\" needs \"particles\": \"unstructured\" (graded regions)");
  }
  remesh_.set_size_field(std::move(size));
}

bool FluidModel::read_scheme(Params s, const FluidDefaults& d, RemeshPipeline::Settings& rs, PspgSettings& ps,
                             FractionalStepSettings& fs) {
  if (!s.json().is_object()) s.fail("must be an object");
  const std::string scheme =
      s.has("type") ? s.choice("type", {"monolithic_pspg", "fractional_step"}) : "monolithic_pspg";
  const bool pspg = scheme == "monolithic_pspg";
  fractional_ = !pspg;
  // The defaults that follow other keys (fluid_defaults); the free-surface pressure is the monolithic scheme's.
  Json derived = {{"volume_correction", d.volume_correction}, {"volume_relaxation_time", d.volume_relaxation_time}};
  if (pspg) derived["free_surface_pressure"] = d.free_surface_pressure;
  // Particle volumes with the fractional step return 5 % of a debt per step, T = 20 dt (a tuned value: its
  // projection answers a debt within the step, and T below about 10 dt over-corrects: the forced sloshing's error
  // grew tenfold at 8 dt; docs/decisions/0007-fractional-step.md).
  if (!pspg && peek(s.json(), "volume_correction", d.volume_correction) == "particle")
    derived["volume_relaxation_time"] = 20.0 * ctx_.analysis.dt;
  expand_linear_solver(s, "linear_solver");
  s.validate(pspg ? kPspgKeys : kFractionalStepKeys, derived);
  if (pspg) {
    Params tau = s.at("tau");
    if (!tau.json().is_object() || !tau.has("type")) tau.fail("type", "required key is missing");
    const std::string tau_type = tau.choice("type", {"automatic", "velocity_scale"});
    if (tau_type == "automatic") {
      tau.validate(kTauAutomaticKeys);
    } else {
      tau.validate(kTauVelocityKeys);
      ps.tau_U = tau.positive("U");
    }
    ps.lumped = s.choice("mass", {"lumped", "consistent"}) == "lumped";
    const std::string fsp = s.choice("free_surface_pressure", {"dirichlet", "natural", "robin"});
    ps.free_surface = fsp == "dirichlet" ? FreeSurfacePressure::dirichlet
                      : fsp == "natural" ? FreeSurfacePressure::natural
                                         : FreeSurfacePressure::robin;
    ps.robin_factor = s.positive("robin_factor");
    ps.tol = s.positive("tolerance");
    ps.refactor_every = s.integer("refactorize_every", 0);
    LinearSolverSettings ls;
    ls.kind = SystemKind::saddle_point;
    ls.block_size = 3;
    ls.direct = "klu";
    ls.type = "auto";
    ls.auto_threshold = kPspgKrylovFrom;
    ps.solver = mpi_run::distribute(read_linear_solver(s, "linear_solver", ls, kPspgDirect));
  } else {
    // Fractional step: lumped or consistent mass, Dirichlet free-surface pressure, symmetric positive definite
    // solves.
    fs.viscous_step = s.choice("viscous_step", {"automatic", "explicit", "implicit"});
    LinearSolverSettings ls;
    ls.kind = SystemKind::symmetric_positive_definite;
    ls.direct = "cholmod";
    ls.type = "auto";
    ls.auto_threshold = kFractionalStepKrylovFrom;
    fs.solver = mpi_run::distribute(read_linear_solver(s, "linear_solver", ls, kFractionalStepDirect));
    fs.retry_inverted = s.choice("inverted_elements", {"retry", "remesh"}) == "retry";
    fs.consistent_mass = s.choice("mass", {"lumped", "consistent"}) == "consistent";
    // The consistent mass's solves are the process's own (the whole matrix on each process); under a distributed
    // solver each process holds only the elements of its rows.
    if (fs.consistent_mass && fs.solver.distributed)
      s.fail("mass",
             "\"consistent\" with the fractional step needs the whole mesh on each process: one process or a "
             "direct \"linear_solver\"");
    // The conservative detections keep the area where the topology does not change, so the steps must keep it
    // too (fractional_step.cpp); the alpha shape re-detects the domain and corrects its area at every remesh.
    fs.exact_area_rate = rs.detection != meshing::DomainDetection::Alpha;
  }
  const std::string vc = s.choice("volume_correction", {"surface", "source", "particle", "none"});
  // "particle" follows each particle through the remesh: merges and splits on the advected mesh, not the
  // alpha shape's removals and insertions between its re-triangulations.
  if (vc == "particle" && rs.detection == meshing::DomainDetection::Alpha)
    s.fail("volume_correction", "\"particle\" needs \"domain_detection\": \"advected\" or \"level_set\"");
  // With the fractional step (p = 0 on the free surface) the surface particles return their area by moves
  // (VolumeCorrection::return_owed_by_moves), the others through their pressure rows.
  volume_.configure(vc == "surface"    ? VolumeCorrection::Type::surface
                    : vc == "source"   ? VolumeCorrection::Type::source
                    : vc == "particle" ? VolumeCorrection::Type::particle
                                       : VolumeCorrection::Type::none,
                    s.positive("volume_relaxation_time"));
  rs.close_fraction = s.non_negative("remove_close_fraction");
  c_.bulk = s.non_negative("bulk_modulus");
  rs.insert_factor = s.non_negative("insert_area_factor");
  rs.flat_fraction = s.non_negative("flat_element_fraction");
  rs.split_factor = s.non_negative("split_edge_factor");
  if (rs.split_factor > 0 && rs.split_factor < 1.0) s.fail("split_edge_factor", "must be 0 (off) or at least 1");
  if (rs.close_fraction >= 0.9) s.fail("remove_close_fraction", "must be below 0.9");
  remesh_.configure(rs);

  return pspg;
}

void FluidModel::build_particles(Params b) {
  const double h = c_.h;
  // Walls first (their particles take precedence over fluid particles at the same place).
  Params walls = b.at("walls");
  FluidWalls& fluid_walls = boundaries_.walls();
  fluid_walls.read(walls, h, ctx_.base_dir);
  if (wall_constraints_ && fluid_walls.inclined() && !scheme_->wall_frames())
    walls.fail(
        "inclined segments (or turning walls) with \"wall_model\": \"constraints\" need the monolithic scheme (the "
        "fractional step constrains the x and y components)");

  std::vector<Vec2> pts;
  std::vector<ParticleKind> kind;
  PointGrid wall_grid(0.5 * h), fluid_grid(0.5 * h);  // the particles so far, for the proximity tests
  if (auto* particles = dynamic_cast<WallParticles*>(&fluid_walls))
    particles->place_particles(walls, h, pts, kind, wall_grid);
  boundaries_input_ = b.at("boundaries");
  boundaries_.read(boundaries_input_, {h, ctx_.base_dir, ""});
  if (boundaries_.open()) {
    if (!c_.remesh) b.fail("boundaries", "an inflow or outflow needs \"remesh\": true");
    if (volume_.type() == VolumeCorrection::Type::particle)
      b.at("scheme").fail("volume_correction",
                          "\"particle\" keeps each particle's own area, which an inflow's new layers and an "
                          "outflow's removals do not have: use \"surface\" or \"source\" (the "
                          "defaults with open boundaries) or \"none\"");
    remesh_.set_open_boundaries([this](const Vec2& x) { return boundaries_.taker(x); },
                                [this](const Vec2& x) { return boundaries_.outlet_strip(x); },
                                [this](int k, long n, double area) { boundaries_.left(k, n, area); },
                                boundaries_.fluid_regions());
    remesh_.set_open_faces([this](const Vec2& x) { return boundaries_.at_open_face(x); });
  }
  const Index n_wall = static_cast<Index>(pts.size());

  // Fluid regions: particles on a square lattice of spacing h (structured) or the nodes of a Delaunay mesh about
  // as dense as that lattice (unstructured); in PFEM mode, fluid particles closer than h/2 to a wall particle
  // are dropped (the wall particle stands for them).
  Params regions = b.at("regions");
  if (regions.size() == 0) regions.fail("at least one fluid region is needed");
  const std::string layout = b.choice("particles", {"structured", "unstructured"});
  std::vector<Index> fixed_conn;                // fixed-connectivity mode: the initial mesh
  std::vector<std::pair<Index, double>> sizes;  // the fluid particles' initial sizes
  // The walls' bounding box (also the start of the domain box below): a region reaching beyond it by more
  // than the walls' own extent (on an axis where they have one) is a typing error (a size 1000 times too
  // large), which would otherwise be meshed into millions of particles before anything else is checked.
  Vec2 wall_lo, wall_hi;
  fluid_walls.bounding_box(wall_lo, wall_hi);
  for (size_t r = 0; r < regions.size(); ++r) {
    Params g = regions.at(r);
    if (!fluid_walls.empty() && g.json().is_object() && g.has("type")) {
      std::vector<Vec2> corners;
      const std::string rt = g.string("type");
      if (rt == "rectangle" && g.has("size")) {
        const Vec2 o = g.has("origin") ? g.vec2("origin") : Vec2::Zero();
        corners = {o, o + g.vec2("size")};
      } else if ((rt == "polygon" || rt == "circle_cut") && g.has("points")) {
        corners = g.points("points");
      }
      for (size_t c = 0; c < corners.size(); ++c)
        for (int axis = 0; axis < 2; ++axis) {
          const Vec2& q = corners[c];
          const double extent = wall_hi[axis] - wall_lo[axis];
          if (extent > 0 && (q[axis] < wall_lo[axis] - extent || q[axis] > wall_hi[axis] + extent)) {
            std::ostringstream os;
            const char* xy = axis ? "y" : "x";
            os << "reaches " << xy << " = " << q[axis] << ", far beyond the walls (" << xy << " from " << wall_lo[axis]
               << " to " << wall_hi[axis] << ")";
            g.fail(rt == "rectangle" ? std::string(c == 0 ? "origin" : "size") : "points/" + std::to_string(c),
                   os.str());
          }
        }
    }
    TriMesh mesh;
    Json mesh_params = {{"size", h}, {"order", 1}, {"type", "unstructured"}};
    if (layout == "structured") {
      if (!g.has("type") || g.string("type") != "rectangle")
        g.fail("type", "structured particles need rectangle regions (use \"particles\": \"unstructured\")");
      g.validate(kStructuredRegionKeys);
      const Vec2 sz = g.vec2("size");
      if (!(sz.x() >= 0.5 * h && sz.y() >= 0.5 * h))
        g.fail("size", "each side must be at least half the particle spacing (" + std::to_string(h) + ")");
      if (!(sz.x() / h * (sz.y() / h) <= 5e6)) g.fail("size", "more than 5 million particles at this spacing");
      mesh_params = {
          {"size", h},
          {"order", 1},
          {"type", "structured"},
          {"divisions", {std::max(1, (int)std::lround(sz.x() / h)), std::max(1, (int)std::lround(sz.y() / h))}},
          {"pattern", "crossed"}};
    }
    const SizeField& size = remesh_.size_field();
    // An adaptive field: the size at the distance from the region's outline (SizeField::initial_size). The mesher
    // takes a bound on the longest edge (SizeField::mesher_size, uniform_mesher_size); the outline stays split at h.
    std::function<double(const Vec2&)> local_size, mesher_bound;
    if (size.adaptive()) {
      local_size = size.initial_size(geometry_loops(g, h));
      mesher_bound = size.mesher_size(local_size);
    } else if (layout == "unstructured") {
      mesher_bound = size.uniform_mesher_size();
    }
    mesh = build_mesh(g, Params(mesh_params, b.file(), g.path() + "/(mesh)"), mesher_bound);
    for (size_t e = 0; e + 2 < mesh.conn.size(); e += 3)
      remesh_.add_region_triangle(
          {mesh.nodes[mesh.conn[e]], mesh.nodes[mesh.conn[e + 1]], mesh.nodes[mesh.conn[e + 2]]});
    std::vector<Index> new_particles;  // this region's, added to the grid after the region
    std::vector<Index> map(mesh.nodes.size(), -1);
    for (size_t k = 0; k < mesh.nodes.size(); ++k) {
      const Vec2& q = mesh.nodes[k];
      // Within h/2 of a wall particle, or on the shared boundary with an earlier region.
      const bool near_wall = wall_grid.find(q, 0.5 * h, pts) >= 0;
      const bool duplicate = r > 0 && fluid_grid.find(q, 1e-9 * h, pts) >= 0;
      if (near_wall || duplicate) continue;
      map[k] = static_cast<Index>(pts.size());
      new_particles.push_back(map[k]);
      sizes.emplace_back(map[k], local_size ? local_size(q) : h);
      pts.push_back(q);
      kind.push_back(ParticleKind::Fluid);
    }
    for (Index j : new_particles) fluid_grid.add(pts[static_cast<size_t>(j)], j);
    if (!c_.remesh) {
      if (regions.size() > 1) regions.fail("fixed connectivity supports one fluid region");
      fixed_conn = mesh.conn;
      for (auto& c : fixed_conn) c = map[c];
    }
  }
  if (pts.size() == static_cast<size_t>(n_wall)) regions.fail("the regions contain no fluid particle");

  if (c_.remesh) remesh_.set_domain(wall_lo, wall_hi, pts);
  fluid_walls.set_fluid_sides(pts, kind);
  cloud_.assign(pts, kind, h);
  for (const auto& [i, s] : sizes) cloud_.set_h(i, s);
  set_initial_state(b, pts, kind);

  if (!c_.remesh) {
    // Fixed connectivity: the initial mesh for the whole run; walls constrain the fluid nodes on them.
    mesh_.tri.clear();
    for (size_t e = 0; e + 2 < fixed_conn.size(); e += 3)
      mesh_.tri.push_back({fixed_conn[e], fixed_conn[e + 1], fixed_conn[e + 2]});
    dynamic_cast<FixedMeshWalls&>(fluid_walls).constrain_fixed_mesh(b, pts, h, scheme_->wall_frames());
  }
}

void FluidModel::set_initial_state(Params b, const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind) {
  const Index np = static_cast<Index>(pts.size());
  Vec& v = cloud_.v();
  Vec& p = cloud_.p();
  const Vec2 v0 = b.vec2("initial_velocity");
  for (Index i = 0; i < np; ++i)
    if (kind[i] == ParticleKind::Fluid) v.segment<2>(2 * i) = v0;

  Params ip = b.at("initial_pressure");
  if (!ip.has("type")) ip.fail("type", "required key is missing");
  const std::string ipt = ip.choice("type", {"zero", "hydrostatic"});
  if (ipt == "hydrostatic") {
    ip.validate(kPressureHydrostaticKeys);
    const double level = ip.number("level");
    const double g = c_.gravity.norm();
    for (Index i = 0; i < np; ++i) p[i] = std::max(0.0, c_.rho * g * (level - pts[i].y()));
  } else {
    ip.validate(kPressureZeroKeys);
  }

  // Analytic initial states (they override initial_velocity and initial_pressure).
  Params is = b.at("initial_state");
  if (!is.has("type")) is.fail("type", "required key is missing");
  const std::string ist = is.choice("type", {"given", "solitary_wave", "taylor_green"});
  if (ist == "taylor_green") {
    // Divergence-free cellular flow of amplitude U on a square [x0, x0 + L]^2 (a test of energy stability:
    // without gravity the kinetic energy of a free blob can only decrease):
    // u = U sin(pi X) cos(pi Y), v = -U cos(pi X) sin(pi Y), X = (x - x0) / L, Y = (y - y0) / L.
    is.validate(kStateTaylorGreenKeys);
    const double U = is.number("amplitude"), Lc = is.positive("length");
    const Vec2 o = is.vec2("origin");
    for (Index i = 0; i < np; ++i) {
      if (kind[i] != ParticleKind::Fluid) continue;
      const double X = std::numbers::pi * (pts[i].x() - o.x()) / Lc, Y = std::numbers::pi * (pts[i].y() - o.y()) / Lc;
      v[2 * i] = U * std::sin(X) * std::cos(Y);
      v[2 * i + 1] = -U * std::cos(X) * std::sin(Y);
    }
  } else if (ist == "solitary_wave") {
    // Laitone (1960) first-order solitary wave of height H on depth d, crest at x0, moving towards +x:
    // eta = d + H sech^2(k (x - x0)), k = sqrt(3H / (4 d^3)),
    // u = sqrt(g d) (H/d) sech^2, v = sqrt(3 g d) (H/d)^(3/2) (y/d) sech^2 tanh, p = rho g (eta - y).
    is.validate(kStateSolitaryKeys);
    const double d = is.positive("depth"), H = is.positive("height"), x0 = is.number("crest");
    const double g = c_.gravity.norm();
    if (!(g > 0)) is.fail("type", "a solitary wave needs gravity");
    const double k = std::sqrt(3 * H / (4 * d * d * d));
    for (Index i = 0; i < np; ++i) {
      if (kind[i] != ParticleKind::Fluid) continue;
      const double xi = k * (pts[i].x() - x0), y = pts[i].y();
      const double sech2 = 1.0 / (std::cosh(xi) * std::cosh(xi));
      v[2 * i] = std::sqrt(g * d) * (H / d) * sech2;
      v[2 * i + 1] = std::sqrt(3 * g * d) * std::pow(H / d, 1.5) * (y / d) * sech2 * std::tanh(xi);
      p[i] = std::max(0.0, c_.rho * g * (d + H * sech2 - y));
    }
  } else {
    is.validate(kStateGivenKeys);
  }
}

}  // namespace lagfsi::fluid
