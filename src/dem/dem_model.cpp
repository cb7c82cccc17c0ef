// The lifecycle of a DEM body (src/dem/include/lagfsi/dem/dem_model.hpp): sub-steps of the shared central
// difference (explicit_step_into) with the force sweep of dem_forces.cpp as the force callback.
#include "dem_body.hpp"
#include "dem_output.hpp"

#include <lagfsi/dem/dem_model.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/stopwatch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lagfsi {

namespace dem {

namespace {}  // namespace

DemModel::DemModel(Params body, const CaseContext& ctx) : ctx_(ctx), body_(std::make_unique<DemBody>()) {
  settle_time_ = read_dem_body(std::move(body), ctx, *body_);
  writer_ = std::make_unique<DemWriter>(ctx.out_dir, body_->csv);
}

DemModel::~DemModel() = default;

std::string DemModel::name() const { return body_->name; }
Index DemModel::num_nodes() const { return static_cast<Index>(body_->size()); }
Index DemModel::num_elements() const { return body_->contact_count(); }

namespace {

double cross(const Vec2& u, const Vec2& w) { return u.x() * w.y() - u.y() * w.x(); }

/// Whether the segments [p0, p1] and [a, b] cross (each one's ends strictly on either side of the other's line).
bool crosses(const Vec2& p0, const Vec2& p1, const Vec2& a, const Vec2& b) {
  const double o1 = cross(b - a, p0 - a), o2 = cross(b - a, p1 - a);
  const double o3 = cross(p1 - p0, a - p0), o4 = cross(p1 - p0, b - p0);
  return ((o1 < 0 && o2 > 0) || (o1 > 0 && o2 < 0)) && ((o3 < 0 && o4 > 0) || (o3 > 0 && o4 < 0));
}

}  // namespace

void DemModel::substep(double h) {
  DemBody& b = *body_;
  if (b.needs_rebuild(h)) {
    check_finite();  // the cell grid of the lists needs finite positions
    b.rebuild();
  }
  b.place_walls(b.state.t + h);
  // The centres of the discs near a wall before the sub-step: a centre that crosses a wall segment in it has
  // been pushed through the wall (or tunnelled through it), which no contact law of the body can undo. A disc
  // that may move more than skin/2 in the sub-step can reach a wall outside its list: it is tested against all.
  near_wall_.clear();
  if (!b.segments.empty() && b.wall_row.size() == b.size() + 1) {
    const double reach2 = 0.25 * b.skin * b.skin;
    for (Index p = 0; p < static_cast<Index>(b.size()); ++p) {
      const Vec2 step = h * b.velocity(p) + 0.5 * h * h * Vec2(b.state.a[3 * p], b.state.a[3 * p + 1]);
      const bool far = step.squaredNorm() > reach2;
      if (far || b.wall_row[p + 1] > b.wall_row[p]) near_wall_.push_back({p, b.position(p), far});
    }
  }
  b.integrator->explicit_step_into(
      [&b, h](const Vec& x, const Vec& v, double t, Vec& f) { b.compute_forces(x, v, t, h, f); }, b.inv_mass, h,
      b.state, b.force);
  for (const NearWall& nw : near_wall_) {
    const Index p = nw.disc;
    const Index n_seg = nw.all_walls ? static_cast<Index>(b.segments.size()) : b.wall_row[p + 1] - b.wall_row[p];
    for (Index k = 0; k < n_seg; ++k) {
      const auto [w, s] = b.segments[nw.all_walls ? k : b.wall_seg[b.wall_row[p] + k]];
      const Wall& wall = b.walls[w];
      const Vec2 c0 = nw.centre, c1 = b.position(p);
      if (!crosses(c0, c1, wall.a(s), wall.b(s))) continue;
      char msg[640];
      std::snprintf(msg, sizeof msg,
                    "dem body '%s': disc %ld crossed wall '%s' from (%.6g, %.6g) to (%.6g, %.6g) at t = %.6g: %s",
                    b.name.c_str(), static_cast<long>(b.discs.id[p]), wall.name.c_str(), c0.x(), c0.y(), c1.x(), c1.y(),
                    b.state.t,
                    b.dt > b.dt_critical ? "the sub-step is above the critical one"
                                         : "the contact cannot hold it (too soft for the load or the initial overlap, "
                                           "or the disc too fast for the sub-step)");
      throw SolverError(msg);
    }
  }
  if (dynamic_cast<const Sabatucci*>(b.law.get())) b.apply_marks();
  // The moving walls' work on the discs over the sub-step (the energy guard): force on the disc times the
  // wall's velocity, at the step's end.
  if (!b.segments.empty() && std::any_of(b.walls.begin(), b.walls.end(), [](const Wall& w) { return w.moving(); }))
    for (Index e = 0; e < static_cast<Index>(b.wall_seg.size()); ++e) {
      const Vec2 vw = b.walls[b.segments[b.wall_seg[e]].first].velocity(b.state.t);
      b.wall_work += h * (b.wall_force[2 * e] * vw.x() + b.wall_force[2 * e + 1] * vw.y());
    }
  ++b.substeps;
}

std::vector<std::string> DemModel::warnings() const { return body_->warnings; }

void DemModel::initialize() {
  DemBody& b = *body_;
  const auto t0 = SteadyClock::now();
  // Here, not when the body is read: `lagfsi check` prints errors alone, and a run's later input error too.
  if (!ctx_.quiet)
    std::fprintf(stderr, "[%s] %zu discs, critical step %.4g s, sub-step %.4g s\n", b.name.c_str(), b.size(),
                 b.dt_critical, b.dt);
  b.state.t = settle_time_ > 0 ? -settle_time_ : 0.0;
  b.place_walls(std::max(b.state.t, 0.0));
  b.rebuild();
  b.compute_forces(b.state.x, b.state.v, b.state.t, 0.0, b.force);
  b.state.a = b.inv_mass.cwiseProduct(b.force);
  if (settle_time_ > 0) {
    // settling: walls held at their t = 0 place; then remove the named walls and start from rest
    const long n = std::max(1L, static_cast<long>(std::ceil(settle_time_ / b.dt * (1 - 1e-12))));
    const double h = settle_time_ / n;
    std::vector<Wall> saved = b.walls;
    for (long k = 0; k < n; ++k) substep(h);
    std::vector<Wall> kept;
    for (auto& w : b.walls)
      if (std::find(b.remove_after_settle.begin(), b.remove_after_settle.end(), w.name) == b.remove_after_settle.end())
        kept.push_back(w);
    b.walls = kept;
    b.segments.clear();
    for (size_t w = 0; w < b.walls.size(); ++w)
      for (size_t s = 0; s < b.walls[w].segments(); ++s)
        b.segments.emplace_back(static_cast<int>(w), static_cast<int>(s));
    b.wall_row.clear();  // no history to carry: the wall indices changed
    b.state.v.setZero();
    b.state.t = 0.0;
    b.place_walls(0.0);
    b.rebuild();
    b.compute_forces(b.state.x, b.state.v, 0.0, 0.0, b.force);
    b.state.a = b.inv_mass.cwiseProduct(b.force);
    b.dissipated = 0;
    b.substeps = 0;
    if (!ctx_.quiet) std::fprintf(stderr, "[%s] settled for %.4g s (%ld sub-steps)\n", b.name.c_str(), settle_time_, n);
  }
  if (b.crater.enabled && b.crater.surface == 0) {  // the ground level: the top of the bed at t = 0
    double top = -1e300;
    for (Index p = 0; p < static_cast<Index>(b.size()); ++p) top = std::max(top, b.position(p).y() + b.discs.radius[p]);
    b.crater.surface = top;
  }
  b.blast_work = 0;
  b.energy0 = b.kinetic_energy() + b.elastic + b.gravity_potential();
  start_energy_guard();
  wall_time_ += seconds_since(t0);
}

void DemModel::start_energy_guard() {
  DemBody& b = *body_;
  // The contacts' elastic energy at t = 0 (initial overlaps): one force sweep with the energy sums on, h = 0
  // (no history advanced), its side effects on the energy probes' sums undone.
  const bool tracked = b.track_energy;
  const double elastic = b.elastic, dissipated = b.dissipated;
  b.track_energy = true;
  Vec f;
  b.compute_forces(b.state.x, b.state.v, b.state.t, 0.0, f);
  const double elastic0 = b.elastic;
  b.track_energy = tracked;
  b.elastic = elastic;
  b.dissipated = dissipated;
  b.wall_work = 0;
  b.energy_ref = b.kinetic_energy() + b.gravity_potential() + elastic0;
  // The scale: what the discs hold (kinetic, elastic) and what gravity can give them over the height of the
  // discs and walls.
  double mass = 0, lo = 1e300, hi = -1e300;
  for (Index p = 0; p < static_cast<Index>(b.size()); ++p) {
    mass += b.discs.mass[p];
    lo = std::min(lo, b.position(p).y() - b.discs.radius[p]);
    hi = std::max(hi, b.position(p).y() + b.discs.radius[p]);
  }
  for (const Wall& w : b.walls)
    for (const Vec2& q : w.points) {
      lo = std::min(lo, q.y() + w.offset.y());
      hi = std::max(hi, q.y() + w.offset.y());
    }
  b.energy_scale = b.kinetic_energy() + std::abs(elastic0) + mass * b.gravity.norm() * (hi - lo);
}

void DemModel::check_finite() const {
  const DemBody& b = *body_;
  for (Index p = 0; p < static_cast<Index>(b.size()); ++p)
    if (!std::isfinite(b.state.x[3 * p]) || !std::isfinite(b.state.x[3 * p + 1]) || !std::isfinite(b.state.v[3 * p]))
      throw SolverError("dem body '" + b.name + "': disc " + std::to_string(b.discs.id[p]) +
                        " has a non-finite position or velocity at t = " + std::to_string(b.state.t) + " (" +
                        (b.dt > b.dt_critical ? "the sub-step is above the critical one: the run is unstable"
                                              : "the forces on it overflowed") +
                        ")");
}

void DemModel::check_energy() const {
  const DemBody& b = *body_;
  // Energy: E = kinetic + gravity potential may exceed the initial total (with the contacts' elastic energy)
  // only by the work put in; the central difference, stable, keeps the error far below energy_scale.
  const double gain = b.kinetic_energy() + b.gravity_potential() - b.energy_ref - b.blast_work - b.wall_work;
  const double allowed = b.energy_scale + std::abs(b.blast_work) + std::abs(b.wall_work);
  if (std::isnan(gain) || (gain > allowed && gain > 1e-12)) {
    char msg[512];
    std::snprintf(msg, sizeof msg,
                  "dem body '%s': the energy grew by %.4g J by t = %.6g, more than the %.4g J the discs held or were "
                  "given at the start (work of the blast and walls included)%s",
                  b.name.c_str(), gain, b.state.t, allowed,
                  b.dt > b.dt_critical ? ": the sub-step is above the critical one, and the run is unstable"
                                       : ": the contact law or its step is unstable");
    throw SolverError(msg);
  }
}

void DemModel::save_step_start() {
  if (snapshot_)
    *snapshot_ = *body_;
  else
    snapshot_ = std::make_unique<DemBody>(*body_);
}

void DemModel::restore_step_start() {
  // Back to the start of the step; the work counters keep the failed attempt's work.
  DemBody& b = *body_;
  const long substeps = b.substeps, rebuilds = b.rebuilds;
  const double t_force = b.t_force, t_rebuild = b.t_rebuild, t_blast = b.t_blast;
  b = *snapshot_;
  b.substeps = substeps;
  b.rebuilds = rebuilds;
  b.t_force = t_force;
  b.t_rebuild = t_rebuild;
  b.t_blast = t_blast;
}

int DemModel::advance(double t_new, double) {
  DemBody& b = *body_;
  const double span = t_new - b.state.t;
  const int n = std::max(1, static_cast<int>(std::ceil(span / b.dt * (1 - 1e-12))));
  const double h = span / n;
  for (int k = 0; k < n; ++k) substep(h);
  b.state.t = t_new;
  check_finite();
  check_energy();
  return n;
}

void DemModel::write_output(double t) {
  const auto t0 = SteadyClock::now();
  writer_->write(t, *body_);
  times_.output += seconds_since(t0);
}

double DemModel::energy_balance() const {
  const DemBody& b = *body_;
  return b.kinetic_energy() + b.elastic + b.gravity_potential() + b.dissipated - b.energy0 - b.blast_work;
}

Json DemModel::summary() const {
  const DemBody& b = *body_;
  int marked = 0;
  for (auto m : b.discs.mark) marked += m;
  Json s{{"discs", b.size()},
         {"contact_law", b.law->type()},
         {"dt_critical", b.dt_critical},
         {"dt", b.dt},
         {"substeps", b.substeps},
         {"list_rebuilds", b.rebuilds},
         {"contacts", b.contact_count()},
         {"marked_discs", marked},
         {"time_forces", b.t_force},
         {"time_rebuild", b.t_rebuild},
         {"time_blast", b.t_blast},
         {"wall_time", wall_time_},
         {"particle_steps_per_second", wall_time_ > 0 ? double(b.substeps) * b.size() / wall_time_ : 0.0}};
  if (settle_time_ > 0) s["settle_time"] = settle_time_;
  return s;
}

}  // namespace dem

std::unique_ptr<PhysicsModel> make_dem_model(Params body, const CaseContext& ctx) {
  return std::make_unique<dem::DemModel>(std::move(body), ctx);
}

}  // namespace lagfsi
