// An inflow: a segment through which water enters the fluid at a prescribed velocity. With the segment from a to b
// (length L, unit tangent t, unit normal n towards the fluid: the side the velocity points to) and the coordinate
// s = (x - a).t / L in [0, 1], the inflow velocity is
//   u(s, t) = U phi(s) f(t),   phi = 1 ("uniform") or 6 s (1 - s) ("parabolic": zero at the ends, mean 1, peak 3/2)
//                             or g(s) / int_0^1 g ds ("table": g interpolated linearly in the case's points (s, f),
//                             constant beyond the first and last; normalized to mean 1 by its exact integral),
// with U the case's mean velocity and f its time function (1 without one): every profile has mean int_0^1 phi ds = 1,
// so U is the mean velocity and the flux through the segment is U.n L f(t) whatever the profile. The segment is
// divided into N = L / h lanes, one at each s_k = k / N, k = 0..N (the spacing of a structured region that starts at
// the segment). What the inflow holds ("hold"):
//  - "points" (the default): one fluid particle fixed at each lane's point of the segment, with the velocity
//    u(s_k, t) (a Dirichlet condition at fixed points, as an Eulerian inlet's nodes), and any other particle that
//    comes within h/4 of the segment moved with the profile: the mesh's inlet is the line of the points, and the
//    discrete flux through it, the trapezoidal rule of u on the lanes, is the same at every step whatever the
//    triangles behind it. The first step, before the points exist, holds the layer.
//  - "layer": every fluid particle in the inlet layer (depth d = (x - a).n in [-h/2, h), s in [0, 1]) follows u
//    over the step in both components (a Dirichlet condition on its motion, as a moving lid's).
//    The linear interpolant of a curved profile on the layer's triangles is not divergence-free, and those
//    triangles change every step: the flux into the flow jitters (by about 0.1 % in Turek & Hron's channel), and
//    every jitter is a pressure kick on the whole confined column of water.
// The held particles' pressures stay unknowns with their continuity equations: the inlet is a boundary of the mesh,
// not a free surface.
//
// Injection (after each step): each lane adds up the distance its inflow velocity carried the fluid,
// d_k += u_n(s_k) int f dt, and when it reaches a spacing, d_k -= h, a new particle enters at depth d_k (where it
// would be had it entered at that instant; h/2 further with "points", in front of the lane's fixed particle) with
// the inflow's velocity and the nearest particle's pressure: particles enter in layers at exactly the rate the profile
// carries them, as in the inflows of Kratos' PFEM and of PFEM-2 (Idelsohn et al. 2013). A lane whose inflow velocity is
// zero (a parabolic profile's ends, which walls hold) gets none, nor does an end lane where a wall's or a structure's
// particle sits within half a spacing of the segment's end (walls of particles: the wall particle at the corner already
// bounds the mesh there, and a particle injected on it would coincide with it). The area that entered is the profile's
// flux, u_n L int f dt (summary.json also counts the particles, each lane's width times h: the trapezoidal rule of phi
// on the lanes, which is 1 - 1/N^2 of the flux for the parabola and 1 for a table whose points are among the lanes').
// The strip of depth 1.5 h behind the segment counts as fluid for the advected and level-set domain detections, so that
// the elements joining a new layer to the flow are kept.
#include "fluid_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace lagfsi::fluid {

namespace {

const KeyTable kInflowKeys(
    "/bodies/*/boundaries/* (fluid body, type inflow)",
    "A segment through which water enters at a prescribed velocity profile; new particles are injected in layers "
    "one spacing apart as the flow advances. Needs remeshing; the domain detection may be any.",
    {{"type", "inflow", "`inflow`."},
     {"name", "boundary", "Boundary name (summary.json); default: boundary<index>.", kDerived},
     {"segment", nullptr, "The inlet segment [[x0, y0], [x1, y1]] (m), on the edge of a fluid region."},
     {"velocity", nullptr,
      "The mean inflow velocity [u, v] (m/s) over the segment, scaled by the profile and the function; it must "
      "point off the segment, into the fluid."},
     {"profile", Json{{"type", "uniform"}},
      "The velocity's shape phi(s) along the segment (s from 0 at its first point to 1 at its second), mean 1: "
      "`uniform` (the velocity everywhere), `parabolic` (6 s (1 - s): zero at its ends, 1.5 times the mean at its "
      "middle: a channel's Poiseuille profile) or a table (see /bodies/*/boundaries/*/profile (fluid body, inflow, "
      "type "
      "table)); a string is short for {\"type\": ...}."},
     {"function", Json::object(),
      "A time function f(t) scaling the velocity (see time function (type ...)), e.g. a smooth start; default {}: "
      "1."},
     {"hold", "points",
      "What carries the profile into the water: `points` (one particle fixed at each lane's point of the segment, "
      "one spacing apart, moving the water at the profile's velocity; new particles enter half a spacing in front "
      "of them: the flux through the inlet is the same at every step) or `layer` (every particle within [-h/2, h) "
      "of the segment moved at the profile's velocity: its triangles change every step and the flux jitters, a "
      "pressure kick on a confined flow; decision 0018)."}});

const KeyTable kBuiltInProfileKeys("/bodies/*/boundaries/*/profile (fluid body, inflow, type uniform or parabolic)",
                                   "A built-in profile: uniform (phi = 1) or parabolic (phi = 6 s (1 - s)).",
                                   {{"type", "uniform", "`uniform` or `parabolic`."}});

const KeyTable kTableProfileKeys(
    "/bodies/*/boundaries/*/profile (fluid body, inflow, type table)",
    "A profile f(s) given at points s along the segment, interpolated linearly between them and constant beyond "
    "the first and last; the inflow divides it by its integral over [0, 1], so that its mean is 1 and the "
    "inflow's velocity stays the mean velocity (only the shape counts: f may be in any unit, e.g. a measured "
    "velocity profile in m/s).",
    {{"type", "table", "`table`."},
     {"s", nullptr,
      "The points' positions along the segment, from 0 (its first point) to 1 (its second), increasing; at least "
      "two."},
     {"f", nullptr, "The profile's values at the points (as many as s), not negative, not all zero."}});

/// The normalized profile phi(s) of an inflow (mean 1 over [0, 1]), read from its "profile": an object with a
/// "type", or its type's name alone (expand_shorthand, before the inflow's keys are validated, makes it the object,
/// so that `lagfsi check` prints one form).
class InflowProfile {
 public:
  static void expand_shorthand(Json& inflow) {
    if (inflow.is_object() && inflow.contains("profile") && inflow.at("profile").is_string())
      inflow["profile"] = Json{{"type", inflow.at("profile")}};
  }

  InflowProfile() = default;
  /// `inflow`: the inflow's object, validated.
  explicit InflowProfile(const Params& inflow) {
    Params p = inflow.at("profile");
    if (!p.has("type")) p.fail("type", "required key is missing (uniform, parabolic or table)");
    const std::string type = p.choice("type", {"uniform", "parabolic", "table"});
    if (type != "table") {
      p.validate(kBuiltInProfileKeys);
      parabolic_ = type == "parabolic";
      return;
    }
    p.validate(kTableProfileKeys);
    read_table(p);
  }

  double operator()(double s) const {
    if (s_.empty()) return parabolic_ ? 6.0 * s * (1.0 - s) : 1.0;
    if (s <= s_.front()) return f_.front();
    if (s >= s_.back()) return f_.back();
    const size_t k = static_cast<size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin());
    const double w = (s - s_[k - 1]) / (s_[k] - s_[k - 1]);
    return (1 - w) * f_[k - 1] + w * f_[k];
  }

 private:
  /// The table's points, checked, and its values divided by the exact integral of the linear interpolant over
  /// [0, 1] (the trapezoidal rule between the points, rectangles beyond them).
  void read_table(const Params& p) {
    s_ = p.numbers("s");
    f_ = p.numbers("f");
    if (s_.size() < 2) p.fail("s", "needs at least two points");
    if (f_.size() != s_.size())
      p.fail("f", "has " + std::to_string(f_.size()) + " values for " + std::to_string(s_.size()) + " points in s");
    for (size_t k = 0; k < s_.size(); ++k) {
      std::string at = std::to_string(k);  // (not "/" + ...: a false -Wrestrict of GCC 12, bug 105329)
      at.insert(0, 1, '/');
      if (s_[k] < 0 || s_[k] > 1) p.fail("s" + at, "must lie in [0, 1] (found " + number_text(s_[k]) + ")");
      if (k > 0 && !(s_[k] > s_[k - 1])) p.fail("s" + at, "must be greater than the point before it");
      if (f_[k] < 0) p.fail("f" + at, "must not be negative (found " + number_text(f_[k]) + ")");
    }
    double mean = f_.front() * s_.front() + f_.back() * (1 - s_.back());
    for (size_t k = 1; k < s_.size(); ++k) mean += 0.5 * (f_[k] + f_[k - 1]) * (s_[k] - s_[k - 1]);
    if (!(mean > 0)) p.fail("f", "must not be zero everywhere (the flux would be zero)");
    for (double& f : f_) f /= mean;
  }
  static std::string number_text(double x) {
    std::ostringstream o;
    o << x;
    return o.str();
  }

  bool parabolic_ = false;
  std::vector<double> s_, f_;  // a table: its points and its normalized values (empty: built in)
};

class Inflow final : public FluidBoundary {
 public:
  Inflow(Params p, const BoundaryContext& ctx) : h_(ctx.h) {
    InflowProfile::expand_shorthand(p.json());
    p.validate(kInflowKeys, {{"name", ctx.name}});
    seg_ = BoundarySegment(p, 0.5 * h_, "shorter than half a particle spacing");
    u_ = p.vec2("velocity");
    const double un = u_.dot(seg_.normal);
    if (!(std::abs(un) > 1e-3 * u_.norm())) p.fail("velocity", "must point off the segment (into the fluid)");
    if (un < 0) seg_.normal = -seg_.normal;
    profile_ = InflowProfile(p);
    fn_ = BoundaryFunction(p, ctx.base_dir);
    lanes_ = std::max<Index>(1, static_cast<Index>(std::lround(seg_.length / h_)));
    points_ = p.choice("hold", {"points", "layer"}) == "points";
  }

  bool open() const override { return true; }
  bool holds_pressure() const override { return true; }
  bool in_inlet(const Vec2& x) const override {
    const Vec2 q = x - seg_.a;
    const double s = q.dot(seg_.tangent) / seg_.length, d = q.dot(seg_.normal);
    return s >= -1e-9 && s <= 1 + 1e-9 && d >= -0.5 * h_ && d < h_ * (1 - 1e-9);
  }

  void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                 std::vector<BoundaryConstraint>& out) override {
    t0_ = t;
    held_velocity_.assign(static_cast<size_t>(cloud.n()), Vec2::Zero());
    fixed_.assign(static_cast<size_t>(cloud.n()), 0);
    long held = 0;
    const bool points = points_ && !lane_point_.empty();
    for (Index i = 0; i < cloud.n(); ++i) {
      if (!cloud.is_fluid(i) || taken[static_cast<size_t>(i)]) continue;
      if (!in_inlet(cloud.pos(i))) continue;
      if (points) {
        // A lane's point is held in place; any other particle that came within a quarter spacing of the segment
        // (behind the points: the new ones enter half a spacing in front) is moved with the profile, forwards.
        if (at_lane_point(cloud.pos(i)))
          fixed_[static_cast<size_t>(i)] = 1;
        else if ((cloud.pos(i) - seg_.a).dot(seg_.normal) >= 0.25 * h_)
          continue;
      }
      const double s = (cloud.pos(i) - seg_.a).dot(seg_.tangent) / seg_.length;
      held_velocity_[static_cast<size_t>(i)] = u_ * profile(s);
      out.push_back({i, 0, cloud.pos(i).x()});
      out.push_back({i, 1, cloud.pos(i).y()});
      ++held;
    }
    held_max_ = std::max(held_max_, held);
  }
  double position(const BoundaryConstraint& k, double t) const override {
    if (fixed_[static_cast<size_t>(k.i)]) return k.base;  // a lane's point: the water moves past it
    return k.base + held_velocity_[static_cast<size_t>(k.i)][k.c] * (integral(t) - integral(t0_));
  }
  double velocity(const BoundaryConstraint& k, double t) const override {
    return held_velocity_[static_cast<size_t>(k.i)][k.c] * value(t);
  }
  double acceleration(const BoundaryConstraint& k, double t) const override {
    return held_velocity_[static_cast<size_t>(k.i)][k.c] * rate(t);
  }

  double after_step(const StepEnd& end) override {
    ParticleCloud& cloud = end.cloud;
    const double t = end.t;
    // Each lane's distance travelled since its last particle entered; a lane that has travelled a spacing gets
    // the next one, where it would be had it entered at that instant (the injected area is the profile's flux).
    const double swept = integral(t) - integral(t0_);
    std::vector<Index> near = near_inlet(cloud);
    const std::vector<char> open = open_lanes(cloud, near);
    if (points_) {
      const Index before = cloud.n();
      place_lane_points(cloud, t, open, near);
      for (Index i = before; i < cloud.n(); ++i) near.push_back(i);
    }
    const double offset = points_ ? 0.5 * h_ : 0.0;
    const auto nl = static_cast<size_t>(lanes_ + 1);
    if (phase_.size() != nl) phase_.assign(nl, 0.0);
    std::vector<ParticleCloud::Particle> added;
    double area = 0.0;
    const double width = seg_.length / static_cast<double>(lanes_);
    for (size_t k = 0; k < nl; ++k) {
      if (!open[k]) continue;
      const double s = static_cast<double>(k) / static_cast<double>(lanes_);
      phase_[k] += u_.dot(seg_.normal) * profile(s) * swept;
      if (phase_[k] < h_ * (1 - 1e-9)) continue;
      phase_[k] = std::max(0.0, phase_[k] - h_);
      added.push_back(entering(cloud, near, lane_position(k) + seg_.normal * (phase_[k] + offset), s, t));
      area += (k == 0 || k + 1 == nl ? 0.5 : 1.0) * width * h_;
    }
    if (!added.empty()) cloud.append(added);
    injected_ += static_cast<long>(added.size());
    area_injected_ += area;
    // What the profile carried in over the step: the mean normal velocity times the length, times int f dt.
    const double flux = u_.dot(seg_.normal) * seg_.length * swept;
    area_prescribed_ += flux;
    return flux;
  }

  void fluid_regions(std::vector<std::array<Vec2, 3>>& out) const override {
    const Vec2 b = seg_.b(), depth = seg_.normal * (1.5 * h_);
    out.push_back({seg_.a, b, b + depth});
    out.push_back({seg_.a, b + depth, seg_.a + depth});
  }

  Json summary() const override {
    return {{"type", "inflow"},
            {"particles_injected", injected_},
            {"area_injected", area_injected_},
            {"area_prescribed", area_prescribed_},
            {"particles_held_max", held_max_}};
  }
  void serialize(StateArchive& ar) override {
    ar.io(t0_, phase_, injected_, area_injected_, area_prescribed_, held_max_, lane_point_);
  }

 private:
  Vec2 lane_position(size_t k) const {
    return seg_.a + seg_.tangent * (static_cast<double>(k) / static_cast<double>(lanes_) * seg_.length);
  }
  /// Whether x is a lane's fixed point (positions held by position() keep it to the bit).
  bool at_lane_point(const Vec2& x) const {
    const long k = std::lround((x - seg_.a).dot(seg_.tangent) / seg_.length * static_cast<double>(lanes_));
    if (k < 0 || k > lanes_ || !lane_point_[static_cast<size_t>(k)]) return false;
    return (x - lane_position(static_cast<size_t>(k))).norm() < 1e-9 * h_;
  }
  /// Per lane: whether it carries water in, its inflow velocity positive and, at an end of the segment, no wall's or
  /// structure's particle there.
  std::vector<char> open_lanes(const ParticleCloud& cloud, const std::vector<Index>& near) const {
    const auto nl = static_cast<size_t>(lanes_ + 1);
    std::vector<char> open(nl, 0);
    for (size_t k = 0; k < nl; ++k)
      open[k] = u_.dot(seg_.normal) * profile(static_cast<double>(k) / static_cast<double>(lanes_)) > 0 &&
                !((k == 0 || k + 1 == nl) && boundary_particle_near(cloud, near, lane_position(k)));
    return open;
  }
  /// The particles within reach of the inlet's searches, in one pass: within [-2h, 4h) of the segment's line along
  /// its normal and within two spacings of its extent (a new particle enters at most 1.5 h in front of the line and
  /// takes the pressure of its nearest fluid neighbour within 2 h; the end lanes look for a wall's particle within
  /// h/2; the lane points for a fluid particle within h/2). The searches cost O(lanes x particles near the inlet),
  /// not O(lanes x particles).
  std::vector<Index> near_inlet(const ParticleCloud& cloud) const {
    std::vector<Index> near;
    for (Index i = 0; i < cloud.n(); ++i) {
      const Vec2 q = cloud.pos(i) - seg_.a;
      const double d = q.dot(seg_.normal), along = q.dot(seg_.tangent);
      if (d >= -2 * h_ && d < 4 * h_ && along >= -2 * h_ && along <= seg_.length + 2 * h_) near.push_back(i);
    }
    return near;
  }
  /// A new fluid particle at x (lane coordinate s) with the inflow's velocity and acceleration at time t and the
  /// pressure of its nearest fluid neighbour.
  ParticleCloud::Particle entering(const ParticleCloud& cloud, const std::vector<Index>& near, const Vec2& x, double s,
                                   double t) const {
    ParticleCloud::Particle q;
    q.kind = ParticleKind::Fluid;
    q.h = h_;
    q.x = q.X0 = x;
    q.v = u_ * (profile(s) * value(t));
    q.a = u_ * (profile(s) * rate(t));
    q.p = nearest_pressure(cloud, near, x);
    return q;
  }
  /// "points": every open lane has a fluid particle at its point with the profile's velocity: the nearest fluid
  /// particle within half a spacing moved there (a remesh may have merged the lane's particle away, or the region's
  /// particles start on the segment), or a new one.
  void place_lane_points(ParticleCloud& cloud, double t, const std::vector<char>& open,
                         const std::vector<Index>& inlet) {
    lane_point_ = open;
    std::vector<ParticleCloud::Particle> added;
    std::vector<Index> near;  // the fluid particles within half a spacing of the segment's line
    for (Index i : inlet)
      if (cloud.is_fluid(i) && std::abs((cloud.pos(i) - seg_.a).dot(seg_.normal)) < 0.5 * h_) near.push_back(i);
    for (size_t k = 0; k < open.size(); ++k) {
      if (!open[k]) continue;
      const double s = static_cast<double>(k) / static_cast<double>(lanes_);
      const Vec2 at = lane_position(k);
      Index nearest = -1;
      double d2 = 0.25 * h_ * h_;
      for (Index i : near)
        if ((cloud.pos(i) - at).squaredNorm() < d2) {
          d2 = (cloud.pos(i) - at).squaredNorm();
          nearest = i;
        }
      if (nearest < 0) {
        added.push_back(entering(cloud, inlet, at, s, t));
        continue;
      }
      cloud.x().segment<2>(2 * nearest) = at;
      cloud.v().segment<2>(2 * nearest) = u_ * (profile(s) * value(t));
      cloud.a().segment<2>(2 * nearest) = u_ * (profile(s) * rate(t));
    }
    if (!added.empty()) cloud.append(added);
  }

  /// Whether a wall's or a structure's particle lies within half a spacing of x.
  bool boundary_particle_near(const ParticleCloud& cloud, const std::vector<Index>& near, const Vec2& x) const {
    for (Index i : near)
      if (!cloud.is_fluid(i) && (cloud.pos(i) - x).squaredNorm() < 0.25 * h_ * h_) return true;
    return false;
  }
  /// The pressure of the fluid particle nearest to x within two spacings (0 without one).
  double nearest_pressure(const ParticleCloud& cloud, const std::vector<Index>& near, const Vec2& x) const {
    double best = 4 * h_ * h_, p = 0.0;
    for (Index i : near) {
      const double d2 = (cloud.pos(i) - x).squaredNorm();
      if (cloud.is_fluid(i) && d2 < best) {
        best = d2;
        p = cloud.p()[i];
      }
    }
    return p;
  }
  double profile(double s) const { return profile_(s); }
  double value(double t) const { return fn_.value(t); }
  double integral(double t) const { return fn_.integral(t); }
  double rate(double t) const { return fn_.rate(t); }

  double h_;
  BoundarySegment seg_;  // the normal towards the fluid
  Vec2 u_;
  InflowProfile profile_;
  BoundaryFunction fn_;
  Index lanes_ = 1;
  double t0_ = 0;
  bool points_ = true;               // "hold": "points" (else "layer")
  std::vector<char> lane_point_;     // per lane: it has a fixed point ("points"; empty before the first step's end)
  std::vector<char> fixed_;          // per particle: held at its place (a lane's point) over the step
  std::vector<Vec2> held_velocity_;  // per particle: its inflow velocity over the step (zero if not held)
  std::vector<double> phase_;        // per lane: the distance travelled since its last particle entered
  long injected_ = 0, held_max_ = 0;
  double area_injected_ = 0, area_prescribed_ = 0;
};

}  // namespace

std::unique_ptr<FluidBoundary> make_inflow_boundary(Params p, const BoundaryContext& ctx) {
  return std::make_unique<Inflow>(std::move(p), ctx);
}

}  // namespace lagfsi::fluid
