// PFEM fluid: particles carrying positions, velocities, accelerations and pressure; the mesh is rebuilt
// from the particles at every step (Delaunay + alpha shape or the advected domain, remesh_pipeline.hpp) or
// kept fixed; a step is solved by the scheme chosen in the case (fluid_scheme.hpp: the monolithic PSPG
// position-pressure system, pspg_scheme.cpp, or the fractional step, fractional_step.cpp). This file is the
// model's lifecycle (initialize, predict, solve_iteration, finalize_step, output) over its pieces
// (fluid_model_impl.hpp).
#include "fluid_model_impl.hpp"

#include <lagfsi/mpi_run.hpp>

#include "fluid_probes.hpp"
#include "pressure_level.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lagfsi {
namespace fluid {

namespace {
/// The free-surface flags with boundaries that hold the fluid particles on them (walls as constraints, or a fixed
/// mesh's): an unshared edge between two held particles is a boundary where it runs along one.
void mark_free_surface(RemeshPipeline& remesh, const FluidBoundaries& boundaries, Index n) {
  remesh.mark_free_surface(boundaries.held(n), [&boundaries](const Vec2& p) { return boundaries.along(p); });
}
}  // namespace

void FluidModel::set_dirichlet(double t_start) {
  boundaries_.update(cloud_, t_start);
  boundaries_.clear_free_surface(mesh_.free);  // an inflow's layer keeps its pressure unknown
  const Index np = cloud_.n();
  const std::vector<ParticleKind>& kind = cloud_.kind();
  std::vector<char>& fixed = step_.fixed;
  const FreeSurfacePressure fsp = scheme_->free_surface_pressure();
  fixed.assign(3 * np, 0);
  for (Index i = 0; i < np; ++i) {
    if (kind[i] != ParticleKind::Fluid) fixed[3 * i] = fixed[3 * i + 1] = 1;
    const bool free_surface = mesh_.free[i] && fsp == FreeSurfacePressure::dirichlet;
    if (!mesh_.connected[i] || free_surface) fixed[3 * i + 2] = 1;
  }
  for (const auto& k : boundaries_.constraints()) fixed[3 * k.i + k.c] = 1;
  if (c_.remesh) boundaries_.fix_outlet_pressure(cloud_, mesh_.free, fixed);
  // Dry wall particles: a wall particle in no element with an interior (non-free-surface) fluid particle
  // is above or beside the free surface (a meniscus element between a surface particle and the wall);
  // its pressure is the free-surface one. Left unknown, its continuity row sees only gravity and builds a
  // suction that pulls the surface particles up the wall (spurious currents in a tank at rest).
  if (fsp != FreeSurfacePressure::natural && c_.remesh) {
    const std::vector<char> wet = mesh_.beside_interior_fluid(kind);
    for (Index i = 0; i < np; ++i)
      if (kind[i] != ParticleKind::Fluid && !wet[i]) fixed[3 * i + 2] = 1;
  }
  // Incompressible water enclosed by walls: its level pinned, or an inflow into it refused.
  if (c_.bulk > 0) return;
  const PressureLevelParts level =
      anchor_pressure_level(mesh_, cloud_, mesh_.free, boundaries_.inlets(cloud_), c_.gravity, c_.bulk, fixed);
  if (level.inflow >= 0)
    boundaries_input_.fail(std::to_string(level.inflow),
                           "body '" + c_.name + "': the inflow '" + boundaries_.name(level.inflow) +
                               "' feeds water enclosed by walls (no free surface, no outflow) that is incompressible "
                               "(\"bulk_modulus\": 0): the water it brings has nowhere to go; add an outflow, leave "
                               "the water a free surface, or give the scheme a bulk_modulus");
}

void FluidModel::hold(double t) {
  boundaries_.find(cloud_, t);
  if (!boundaries_.finds_contacts()) return;
  mark_free_surface(remesh_, boundaries_, cloud_.n());
  boundaries_.settle(mesh_.free);
}

// ------------------------------------------------------------------------------------------ lifecycle

void FluidModel::initialize() {
  // The step the driver will take (the analysis' nominal one): what the kernels see before the first predict().
  step_.dt = ctx_.analysis.dt;
  const auto t0 = SteadyClock::now();
  const Index np = cloud_.n();
  const std::vector<ParticleKind>& kind = cloud_.kind();
  if (c_.remesh) {
    remesh_.initial_mesh();
    hold(0.0);
  } else {
    // Free surface of the fixed mesh: nodes of unshared edges that do not lie on a wall.
    mark_free_surface(remesh_, boundaries_, np);
  }
  remesh_.free_regions();  // only the initial domain needs them
  volume_.start(mesh_.area(cloud_.x()));
  n_initial_ = np;
  KinematicState& s = cloud_.state();
  Vec& p = cloud_.p();
  double ymin = 1e300, ymax = -1e300;
  for (Index i = 0; i < np; ++i)
    if (kind[i] == ParticleKind::Fluid) {
      ymin = std::min(ymin, s.x[2 * i + 1]);
      ymax = std::max(ymax, s.x[2 * i + 1]);
    }
  // Pressure scale of the convergence test: hydrostatic, initial and dynamic (rho v^2: a flow without gravity).
  double v2 = 0;
  for (Index i = 0; i < np; ++i) v2 = std::max(v2, s.v.segment<2>(2 * i).squaredNorm());
  step_.p_scale =
      std::max({c_.rho * c_.gravity.norm() * (ymax - ymin), p.cwiseAbs().maxCoeff(), c_.rho * v2, kNoPressureScale});
  // Initial acceleration from the momentum equation with the lumped mass, the initial pressure (zero on
  // the free surface, as the solver will impose) and the initial velocity. An inconsistent a0 excites the
  // period-2 pressure oscillation of the trapezoidal rule on this index-2 system (a hydrostatic column
  // started with a0 = g alternates between 0 and twice the hydrostatic pressure).
  set_dirichlet(0.0);
  for (Index i = 0; i < np; ++i)
    if (step_.fixed[3 * i + 2]) p[i] = 0.0;
  // The element kernel's momentum rows with zero acceleration are the viscous, pressure and gravity
  // forces r = f_visc - f_p - m g; with the lumped mass m_i, a0_i = -r_i / m_i.
  Vec force = Vec::Zero(2 * np), mass = Vec::Zero(np);
  const Vec zero = Vec::Zero(2 * np);
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    Eigen::Matrix<double, 9, 1> r;
    Eigen::Matrix<double, 9, 9> K;
    double i2 = 0, g2 = 0;
    if (!pspg_element(scheme_->element_input(e, s.x, s.v, zero, 0.0, 0.0), r, K, i2, g2)) continue;
    const double m = c_.rho * mesh_.element_area(s.x, e) / 3.0;
    for (int k = 0; k < 3; ++k) {
      force.segment<2>(2 * mesh_.tri[e][k]) -= r.segment<2>(3 * k);
      mass[mesh_.tri[e][k]] += m;
    }
  }
  for (Index i = 0; i < np; ++i) {
    if (kind[i] != ParticleKind::Fluid) continue;
    s.a.segment<2>(2 * i) = mass[i] > 0 ? Vec2(force.segment<2>(2 * i) / mass[i]) : c_.gravity;
  }
  for (const auto& k : boundaries_.constraints()) {
    boundaries_.frames().set_component(s.a, k.i, k.c, 0.0);
    boundaries_.frames().set_component(s.v, k.i, k.c, 0.0);
  }
  boundaries_.set_motion(0.0, s.v, s.a);
  times_.assembly += seconds_since(t0);
}

void FluidModel::predict(double t_new, double dt) {
  auto t0 = SteadyClock::now();
  // A retry of a failed step (the driver calls predict again with a smaller dt): start again from the
  // step's initial pressures. The failed attempt left its own in p, and taking them as the start of the
  // retry compounded the failure (a projection velocity growing like 1/dt at every halving).
  // The cloud's state (x, v, a) is only changed by finalize_step, so the retry starts from it as it is, and the
  // step's mesh is kept: it was built from that same state (the remeshing does not depend on t_new or dt), and
  // remeshing again would insert and remove particles a second time, unlike a clean step of the smaller dt.
  // A remesh that failed (e.g. all the fluid left the domain box) is not kept: the retry remeshes again, and
  // fails again with the same message once the driver runs out of retries. Its particle management may have
  // changed the cloud already (merged, inserted, dropped particles) before the triangulation failed, so the
  // pressures are those the cloud carries (no solve changed them); the step's initial ones (p_old, of the
  // last step's cloud) would no longer fit it (dam_break_obstacle read past the end of the pressures).
  const bool retry = step_open_;
  const bool keep_mesh = retry && step_meshed_;
  if (keep_mesh) cloud_.p() = step_.p_old;
  step_open_ = true;
  step_.t_new = t_new;
  step_.dt = dt;
  if (c_.remesh && solved_once_ && !keep_mesh) {
    step_meshed_ = false;
    // The particles on walls (those put on one at the end of the last step included): merging keeps them there.
    boundaries_.find(cloud_, t_new - dt);
    const std::vector<char> on_wall = boundaries_.finds_contacts() ? boundaries_.held(cloud_.n()) : std::vector<char>();
    if (const FluidWalls& walls = boundaries_.walls(); walls.moving()) {  // the domain box follows them
      Vec2 lo, hi;
      walls.bounding_box_at(t_new - dt, lo, hi);
      remesh_.follow_walls(lo, hi);
    }
    remesh_.remesh_step(t_new, volume_, energy_, on_wall);
  }
  hold(t_new - dt);
  step_meshed_ = true;
  times_.remesh += seconds_since(t0);
  t0 = SteadyClock::now();
  solved_once_ = true;
  mesh_.flatten();
  set_dirichlet(t_new - dt);
  // Particle volumes with the fractional step: the free-surface particles (p = 0, no continuity row) return what
  // they are owed by moves along the gradient of the area, in this step; handed inward, the interior's sources
  // leaked it back into their shares (docs/decisions/0007-fractional-step.md).
  const bool by_moves = fractional_ && volume_.type() == VolumeCorrection::Type::particle;
  if (by_moves) {
    std::vector<char> held(2 * cloud_.n(), 0);
    for (const auto& k : boundaries_.constraints()) held[2 * k.i + k.c] = 1;
    volume_.return_owed_by_moves(step_.fixed, held);
  }
  volume_.set_remeshed(mesh_.area(cloud_.x()), dt);
  if (!by_moves) volume_.hand_owed_inward(step_.fixed);
  volume_.return_unpayable_through_bulk(step_.fixed);
  // A new mesh: new matrices (the scheme's patterns; its integrator starts the step).
  scheme_->begin_step();
  step_.p_old = cloud_.p();
  ghosts_.update_contact(mesh_);
  start_iterations();
  times_.assembly += seconds_since(t0);
}

void FluidModel::start_iterations() {
  const Index np = cloud_.n();
  const KinematicState& s = cloud_.state();
  Vec& x = step_.x;
  Vec& p = cloud_.p();
  p = step_.p_old;
  x = s.x + step_.dt * s.v;                        // constant-velocity predictor
  boundaries_.place(step_.t_new, cloud_.X0(), x);  // prescribed wall motion, particles on walls and boundaries
  ghosts_.place(x);
  for (Index i = 0; i < np; ++i)
    if (step_.fixed[3 * i + 2]) p[i] = 0.0;
  scheme_->restart();
}

IterationReport FluidModel::solve_iteration() { return scheme_->iterate(); }

void FluidModel::finalize_step() {
  step_open_ = false;
  if (energy_.enabled())
    energy_.account(step_.x, scheme_->step_velocity(), step_.t_new, step_.dt, step_.boundary_force,
                    step_.constraint_force);
  const Vec x_start = cloud_.x();
  scheme_->end_step();
  // The walls put back or on a wall the particles that crossed or reached one, a ceiling lets go of those it
  // pulls, an inflow adds its new particles.
  const double entered = boundaries_.after_step(cloud_, x_start, step_.t_new, mesh_, step_.constraint_force);
  if (entered > 0) volume_.add_entered(entered);
  volume_.set_end(mesh_.area(cloud_.x()));
  step_.p_scale = std::max(step_.p_scale, cloud_.p().cwiseAbs().maxCoeff());
}

StepLimit FluidModel::stable_step(double courant) const {
  // A Lagrangian Courant limit: the mesh moves with the fluid, so a step is limited by how much it deforms the
  // elements, not by how far it carries them. Over every edge (a, b) of the step's mesh, Δt |v_a - v_b| <= C |x_a -
  // x_b| (an edge changes its length or turns by at most C of itself; a uniform motion, a film or a jet in one piece,
  // limits nothing); over the fluid particles outside the mesh (drops in flight, which meet the rest only when they
  // land), Δt |v_i| <= C h_i (Courant, Friedrichs & Lewy 1928); and over every fluid particle the acceleration limit
  // C sqrt(h_i / |a_i|) (started from rest, it moves at most C^2 h_i / 2: the force criterion of SPH, Monaghan 1992),
  // which sets the first steps of a flow at rest.
  StepLimit l;
  const KinematicState& s = cloud_.state();
  const auto limit = [&](double dt, const char* by) {
    if (dt < l.dt) {
      l.dt = dt;
      l.by = by;
    }
  };
  for (const auto& t : mesh_.tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];  // an interior edge twice: the same limit
      const double dv = (s.v.segment<2>(2 * a) - s.v.segment<2>(2 * b)).norm();
      const double le = (s.x.segment<2>(2 * a) - s.x.segment<2>(2 * b)).norm();
      if (le > 0 && dv * l.dt > courant * le) limit(courant * le / dv, "courant");
    }
  for (Index i = 0; i < cloud_.n(); ++i) {
    if (!cloud_.is_fluid(i)) continue;
    const double h = cloud_.h(i), a = s.a.segment<2>(2 * i).norm();
    if (mesh_.connected.size() != static_cast<size_t>(cloud_.n()) || !mesh_.connected[i]) {
      const double v = s.v.segment<2>(2 * i).norm();
      if (v * l.dt > courant * h) limit(courant * h / v, "courant");
    }
    if (a * l.dt * l.dt > courant * courant * h) limit(courant * std::sqrt(h / a), "acceleration");
  }
  return l;
}

// ------------------------------------------------------------------------------------------ ghosts

int FluidModel::add_ghosts(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent) {
  if (!c_.remesh) throw std::invalid_argument("body '" + c_.name + "': ghost particles need \"remesh\": true");
  const int merged = ghosts_.add(points, adjacent, cloud_, c_.h, c_.name);
  remesh_.extend_domain(points);  // the domain box holds the structure's boundary too
  return merged;
}

void FluidModel::set_ghost_motion(const Vec& x, const Vec& v, const Vec& a) {
  ghosts_.set_motion(x, v, a, c_.name);
  if (step_.x.size() == cloud_.x().size()) ghosts_.place(step_.x);
}

// ------------------------------------------------------------------------------------------ output

Json FluidModel::summary() const {
  const RemeshPipeline::Settings& rs = remesh_.settings();
  const char* detection = rs.detection == meshing::DomainDetection::Alpha      ? "alpha"
                          : rs.detection == meshing::DomainDetection::Advected ? "advected"
                                                                               : "level_set";
  Json remeshing = remesh_.summary();
  remeshing["domain_detection"] = c_.remesh ? detection : "none (fixed connectivity)";
  remeshing["volume_correction_energy"] = volume_.correction_energy();
  Json s = {{"fluid_area", volume_.summary()},
            {"wall_model", boundaries_.walls().model()},
            {"wall_friction", boundaries_.walls().navier() ? "navier" : "held"},
            {"wall_crossings", boundaries_.walls().crossings()},
            {"wall_snaps", boundaries_.walls().snaps()},
            {"wall_releases", boundaries_.walls().releases()},
            {"inverted_elements_kept", scheme_->inverted_kept()},
            {"linear_solvers", scheme_->linear_solvers()},
            {"particles", {{"initial", n_initial_}, {"final", cloud_.n()}}},
            {"remeshing", remeshing}};
  if (!boundaries_.empty()) s["boundaries"] = boundaries_.summary();
  return s;
}

bool FluidModel::writes_pieces() const { return mpi_run::size() > 1; }

namespace {

/// The piece of `whole` (a mesh of triangles on `mesh`'s points, its point fields per point) that this MPI process
/// writes: the elements whose first particle has its rows here (mpi_run::owned_blocks) and the particles they use,
/// and the process's own particles in no element (drops); the points renumbered, the fields following them.
VtuData piece_of(const TriMesh& mesh, const VtuData& whole, TriMesh& piece_mesh) {
  const auto np = static_cast<Index>(mesh.nodes.size());
  const auto [lo, hi] = mpi_run::owned_blocks(np);
  std::vector<Index> local(static_cast<size_t>(np), -1);
  std::vector<char> used(static_cast<size_t>(np), 0);
  std::vector<Index> points;
  const auto take = [&](Index i) {
    if (local[i] < 0) {
      local[i] = static_cast<Index>(points.size());
      points.push_back(i);
    }
  };
  piece_mesh.order = 1;
  for (size_t k = 0; k + 2 < mesh.conn.size(); k += 3) {
    for (int a = 0; a < 3; ++a) used[mesh.conn[k + a]] = 1;
    if (mesh.conn[k] < lo || mesh.conn[k] >= hi) continue;
    for (int a = 0; a < 3; ++a) {
      take(mesh.conn[k + a]);
      piece_mesh.conn.push_back(local[mesh.conn[k + a]]);
    }
  }
  for (Index i = lo; i < hi; ++i)
    if (!used[i]) take(i);
  for (Index i : points) piece_mesh.nodes.push_back(mesh.nodes[i]);
  VtuData piece;
  piece.mesh = &piece_mesh;
  for (const Field& f : whole.point_fields) {
    Field g{f.name, f.n_components, {}};
    for (Index i : points)
      for (int c = 0; c < f.n_components; ++c)
        g.values.push_back(f.values[static_cast<size_t>(i * f.n_components + c)]);
    piece.point_fields.push_back(std::move(g));
  }
  return piece;
}

}  // namespace

void FluidModel::write_piece(double t, const TriMesh& mesh, const VtuData& whole) {
  TriMesh piece_mesh;
  series_->write_piece(t, piece_of(mesh, whole, piece_mesh), mpi_run::rank(), mpi_run::size());
}

void FluidModel::write_output(double t) {
  const auto t0 = SteadyClock::now();
  if (!series_) series_ = std::make_unique<PvdSeries>(ctx_.out_dir, c_.name);
  const Index np = cloud_.n();
  const Vec& x = cloud_.x();
  const Vec& v = cloud_.v();
  const Vec& p = cloud_.p();
  TriMesh mesh;
  mesh.order = 1;
  mesh.nodes.resize(np);
  for (Index i = 0; i < np; ++i) mesh.nodes[i] = x.segment<2>(2 * i);
  mesh.conn = mesh_.conn.size() == 3 * mesh_.tri.size() ? mesh_.conn : std::vector<Index>();
  if (mesh.conn.empty())
    for (const auto& tr : mesh_.tri) mesh.conn.insert(mesh.conn.end(), tr.begin(), tr.end());
  VtuData d;
  d.mesh = &mesh;
  Field vel{"velocity", 2, {}}, pres{"pressure", 1, {}}, fs{"free_surface", 1, {}}, kd{"kind", 1, {}},
      id{"particle_id", 1, {}};
  for (Index i = 0; i < np; ++i) {
    vel.values.push_back(v[2 * i]);
    vel.values.push_back(v[2 * i + 1]);
    pres.values.push_back(p[i]);
    fs.values.push_back(mesh_.free.empty() ? 0.0 : mesh_.free[i]);
    kd.values.push_back(static_cast<double>(cloud_.kind(i)));
    id.values.push_back(i);
  }
  d.point_fields = {vel, pres, fs, kd, id};
  if (remesh_.size_field().adaptive()) {  // the particles' sizes (the size field's targets at the last remesh)
    Field hs{"particle_size", 1, {}};
    for (Index i = 0; i < np; ++i) hs.values.push_back(cloud_.h(i));
    d.point_fields.push_back(hs);
  }
  if (volume_.type() == VolumeCorrection::Type::particle) {  // the area each particle is owed, over h^2
    Field ow{"owed_area", 1, {}};
    for (Index i = 0; i < np; ++i) ow.values.push_back(cloud_.owed()[i] / (cloud_.h(i) * cloud_.h(i)));
    d.point_fields.push_back(ow);
  }
  if (writes_pieces())
    write_piece(t, mesh, d);
  else
    series_->write(t, d);
  if (!mpi_run::writer()) return;  // the walls' series: process 0's
  if (c_.remesh && !boundaries_.walls().empty()) {
    if (!wall_series_) wall_series_ = std::make_unique<PvdSeries>(ctx_.out_dir, c_.name + "_walls");
    VtpData w;
    Field wp{"pressure", 1, {}};
    for (const auto& wall : boundaries_.walls().all()) {
      std::vector<Index> line;
      for (Index j : wall.particles) {
        line.push_back(static_cast<Index>(w.points.size()));
        w.points.push_back(x.segment<2>(2 * j));
        wp.values.push_back(p[j]);
      }
      if (wall.particles.empty())  // "wall_model": "constraints": the polyline (the pressures are the fluid's)
        for (const Vec2& q : wall.polyline) {
          line.push_back(static_cast<Index>(w.points.size()));
          w.points.push_back(wall.point_at(q, t));
          wp.values.push_back(0.0);
        }
      w.lines.push_back(line);
    }
    w.point_fields = {wp};
    wall_series_->write(t, w);
  }
  times_.output += seconds_since(t0);
}

std::unique_ptr<Probe> FluidModel::make_probe(Params p) {
  const std::string t = p.choice(
      "type", {"front", "column_height", "pressure", "elevation", "runup", "water_above", "discharge", "velocity",
               "fluid_area", "water_area", "kinetic_energy", "potential_energy", "gravity_work", "viscous_dissipation",
               "volume_correction_energy", "total_energy", "boundary_work", "max_speed", "wall_force"});
  if (t == "wall_force" || (t == "pressure" && p.json().contains("method") && p.json().at("method") == "load"))
    request_boundary_forces();
  // The work of gravity, the dissipation and the boundary work are summed over the run only when a probe
  // asks for them (an extra element loop per step).
  if (t == "gravity_work" || t == "viscous_dissipation" || t == "total_energy" || t == "boundary_work") {
    energy_.enable();
    step_.energy = true;
  }
  return make_fluid_probe(*this, p.string("name"), t, p);
}

int FluidModel::wall_index(const std::string& name) const {
  const auto& all = boundaries_.walls().all();
  for (size_t w = 0; w < all.size(); ++w)
    if (all[w].name == name) return static_cast<int>(w);
  return -1;
}

template <class Visit>
void FluidModel::each_constraint_load(const Visit& visit) const {
  // The reaction of each constrained component (the force the wall applies to the fluid along it, sign flipped),
  // and the friction of the particles sliding on a no-slip wall ("navier": -k (v_t - v_wall,t) on the fluid, sign
  // flipped).
  const auto& ks = boundaries_.constraints();
  const ParticleFrames& frames = boundaries_.frames();
  if (static_cast<size_t>(step_.constraint_force.size()) == ks.size())
    for (size_t k = 0; k < ks.size(); ++k)
      if (ks[k].boundary == 0)
        visit(ks[k].i, ks[k].part,
              Vec2(-step_.constraint_force[static_cast<Index>(k)] * frames.direction(ks[k].i, ks[k].c)));
  for (const BoundaryFriction& w : boundaries_.frictions())
    if (w.boundary == 0 && w.i < cloud_.n())
      visit(w.i, w.part,
            Vec2(boundaries_.friction_coefficient(w) *
                 (frames.component(cloud_.v(), w.i, w.c) - boundaries_.friction_velocity(w, step_.t_new)) *
                 frames.direction(w.i, w.c)));
}

std::vector<FluidModel::WallLoad> FluidModel::wall_loads() const {
  std::vector<WallLoad> loads;
  if (boundaries_.walls().finds_contacts()) {
    std::vector<Index> slot(static_cast<size_t>(cloud_.n()), -1);
    each_constraint_load([&](Index i, int, const Vec2& force) {
      if (slot[static_cast<size_t>(i)] < 0) {
        slot[static_cast<size_t>(i)] = static_cast<Index>(loads.size());
        loads.push_back({cloud_.x().segment<2>(2 * i), Vec2::Zero()});
      }
      loads[static_cast<size_t>(slot[static_cast<size_t>(i)])].force += force;
    });
    return loads;
  }
  const Index nb = static_cast<Index>(step_.boundary_force.size() / 2);
  std::vector<char> done(static_cast<size_t>(nb), 0);
  for (const Wall& w : boundaries_.walls().all())
    for (Index j : w.particles)
      if (j < nb && !done[static_cast<size_t>(j)]) {
        done[static_cast<size_t>(j)] = 1;
        loads.push_back({cloud_.x().segment<2>(2 * j), -step_.boundary_force.segment<2>(2 * j)});
      }
  return loads;
}

Vec2 FluidModel::wall_normal_near(const Vec2& p, double& distance) const {
  distance = std::numeric_limits<double>::infinity();
  Vec2 n = Vec2::Zero();
  for (const Wall& w : boundaries_.walls().all())
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k)
      if (const double d = w.distance_at(k, p, step_.t_new); d < distance) {
        distance = d;
        n = w.normal_at(k, step_.t_new);
      }
  return n;
}

Vec2 FluidModel::wall_force(int wall) const {
  Vec2 f = Vec2::Zero();
  if (boundaries_.walls().finds_contacts()) {
    each_constraint_load([&](Index, int part, const Vec2& force) {
      if (part == wall) f += force;
    });
    return f;
  }
  // Wall particles: the force each applied to the fluid in the step's solve. A particle shared by two walls (a
  // corner) splits its force along the two walls' normals there, f = a n1 + b n2 (each wall takes its own
  // normal's part: the pressure on its half of the corner), half each where they are parallel (a joint).
  const auto& all = boundaries_.walls().all();
  const Index nb = static_cast<Index>(step_.boundary_force.size() / 2);
  // The normal of the segment of wall w nearest to particle j.
  const auto normal_at = [&](const Wall& w, Index j) {
    size_t best = 0;
    double d = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k)
      if (const double dk = w.distance(k, cloud_.X0().segment<2>(2 * j), Vec2::Zero()); dk < d) {
        d = dk;
        best = k;
      }
    return w.fluid_normal(best);
  };
  // How many walls hold each particle (a closed polyline lists its first particle twice: it counts once).
  std::vector<int> walls_of(static_cast<size_t>(nb), 0), last(static_cast<size_t>(nb), -1);
  for (size_t w = 0; w < all.size(); ++w)
    for (Index j : all[w].particles)
      if (j < nb && last[static_cast<size_t>(j)] != static_cast<int>(w)) {
        ++walls_of[static_cast<size_t>(j)];
        last[static_cast<size_t>(j)] = static_cast<int>(w);
      }
  std::vector<char> done(static_cast<size_t>(nb), 0);
  std::vector<int> others;
  for (Index j : all[static_cast<size_t>(wall)].particles) {
    if (j >= nb || done[static_cast<size_t>(j)]) continue;
    done[static_cast<size_t>(j)] = 1;
    const Vec2 fj = step_.boundary_force.segment<2>(2 * j);
    others.clear();
    if (walls_of[static_cast<size_t>(j)] > 1)
      for (size_t w = 0; w < all.size(); ++w)
        if (static_cast<int>(w) != wall &&
            std::find(all[w].particles.begin(), all[w].particles.end(), j) != all[w].particles.end())
          others.push_back(static_cast<int>(w));
    if (others.empty()) {
      f -= fj;
      continue;
    }
    if (others.size() == 1) {
      const Vec2 n1 = normal_at(all[static_cast<size_t>(wall)], j);
      const Vec2 n2 = normal_at(all[static_cast<size_t>(others[0])], j);
      const double det = cross(n1, n2);
      if (std::abs(det) > 1e-6) {
        f -= cross(fj, n2) / det * n1;  // fj = a n1 + b n2: a = (fj x n2) / (n1 x n2)
        continue;
      }
    }
    f -= fj / static_cast<double>(others.size() + 1);
  }
  return f;
}

}  // namespace fluid

std::unique_ptr<PhysicsModel> make_fluid_model(Params body, const CaseContext& ctx) {
  return std::make_unique<fluid::FluidModel>(std::move(body), ctx);
}

}  // namespace lagfsi
