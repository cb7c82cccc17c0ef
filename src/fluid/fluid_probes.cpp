// The fluid's probes (fluid_probes.hpp): front, column height, elevation, pressure on a segment, the run-up on a
// wall, the share of the water above a level, area and energies, sampled from the model's read accessors.
#include "fluid_probes.hpp"

#include "fluid_model_impl.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lagfsi::fluid {
namespace {

const KeyTable kFrontKeys("/probes/* (fluid body, type front)",
                          "The largest x (m) of the fluid within a band above the floor.",
                          probe_keys({"front"}, {{"floor", 0.0, "Height (m) of the floor."},
                                                 {"band", 0.0,
                                                  "Height (m) of the band above the floor; default: 2 h "
                                                  "(at least h / 4).",
                                                  kDerived}}));

const KeyTable kColumnHeightKeys("/probes/* (fluid body, type column_height)",
                                 "The largest y (m) of the fluid within a band next to the left wall.",
                                 probe_keys({"column_height"}, {{"wall", 0.0, "x (m) of the wall."},
                                                                {"band", 0.0,
                                                                 "Width (m) of the band next to the wall; default: "
                                                                 "2 h (at least h / 4).",
                                                                 kDerived}}));

const KeyTable kElevationKeys(
    "/probes/* (fluid body, type elevation)", "The free-surface height (m) on a vertical line.",
    probe_keys({"elevation"},
               {{"x", nullptr, "x (m) of the vertical line."},
                {"method", "mesh",
                 "mesh (the highest point of the meshed fluid on the line) or particles (the highest particle "
                 "within the band; biased upwards by the surface's noise)."},
                {"band", 0.0, "Particles method: half-width (m) of the band; default: 1.5 h (at least h / 4).",
                 kDerived}}));

const KeyTable kPressureKeys(
    "/probes/* (fluid body, type pressure)",
    "The mean pressure (Pa) on a sensor segment; with \"from\" equal to \"to\", a point sensor: the pressure "
    "interpolated (P1) in the element that holds the point, 0 where no element does (dry).",
    probe_keys({"pressure"},
               {{"from", nullptr, "One end of the segment [x, y] (m)."},
                {"to", nullptr, "The other end [x, y] (m)."},
                {"tolerance", 0.0, "Distance (m) from the segment within which particles count; default: h / 2.",
                 kDerived},
                {"method", "particles",
                 "particles (the mean pressure of the particles on the segment) or load (a segment on a wall: the "
                 "force the fluid applied to the wall there in the step, along the wall's normal, over the "
                 "segment's length, as a transducer of that face reads it; each particle the wall holds counts "
                 "with its share of the wall, half-way to its neighbours along it, that lies on the segment: the "
                 "reactions of the walls' constraints or the forces on the wall particles, wall_force's, the "
                 "momentum of water stopped by the wall included; 0 where no particle is held, and at the start)."}}));

const KeyTable kRunupKeys("/probes/* (fluid body, type runup)",
                          "The run-up (m): the largest y of the meshed (connected) fluid within a band along a wall "
                          "segment; drops and a jet that left the wall do not count.",
                          probe_keys({"runup"}, {{"from", nullptr, "One end of the wall segment [x, y] (m)."},
                                                 {"to", nullptr, "The other end [x, y] (m)."},
                                                 {"band", 0.0,
                                                  "Distance (m) from the segment within which particles count; "
                                                  "default: 1.5 h.",
                                                  kDerived}}));

const KeyTable kWaterAboveKeys("/probes/* (fluid body, type water_above)",
                               "The share (0-1) of the fluid particles above a level, meshed or in flight.",
                               probe_keys({"water_above"}, {{"level", nullptr, "The level y (m)."}}));

const KeyTable kDischargeKeys(
    "/probes/* (fluid body, type discharge)",
    "The flow rate (m^2/s per m of thickness) through a segment, the integral of u.n over the part of it in the "
    "meshed fluid (P1 velocity); n points to the right of the segment seen from `from` to `to` (from (x, 0) to "
    "(x, H): the flow in +x).",
    probe_keys({"discharge"}, {{"from", nullptr, "One end of the segment [x, y] (m)."},
                               {"to", nullptr, "The other end [x, y] (m)."}}));

const KeyTable kVelocityKeys("/probes/* (fluid body, type velocity)",
                             "A component of the fluid's velocity (m/s) at a point, interpolated in the element "
                             "that holds it (P1); nan where no element does.",
                             probe_keys({"velocity"}, {{"at", nullptr, "The point [x, y] (m)."},
                                                       {"component", nullptr, "`x` or `y`."}}));

const KeyTable kWallForceKeys(
    "/probes/* (fluid body, type wall_force)",
    "A component of the force (N per m of thickness) the fluid applied to a wall in the step, pressure and viscous "
    "stress together: the drag and lift of an obstacle, the weight of water at rest on a floor (negative: "
    "downwards). With \"wall_model\": \"constraints\": the reactions of the wall's constraints on the fluid "
    "particles on it, sign flipped (a particle held at a corner of two walls gives each wall the component along "
    "its normal; at a corner of an inclined wall, both to the inclined one), plus the Navier friction of the "
    "particles sliding on it. With wall particles: the forces its particles applied to the fluid, sign flipped (a "
    "corner particle shared by two walls splits its force along their normals, f = a n1 + b n2). Zero at t = 0.",
    probe_keys({"wall_force"}, {{"wall", nullptr, "The name of a wall of the body (/bodies/i/walls/j/name)."},
                                {"component", nullptr, "`x` or `y`."}}));

const KeyTable kGlobalKeys(
    "/probes/* (fluid body, type fluid_area, water_area, kinetic_energy, ...)",
    "A quantity of the whole fluid: fluid_area (m^2), water_area (with particles in flight), kinetic_energy, "
    "potential_energy, gravity_work, viscous_dissipation, volume_correction_energy, total_energy, boundary_work "
    "(J per m of thickness), max_speed (m/s).",
    probe_keys({"fluid_area", "water_area", "kinetic_energy", "potential_energy", "gravity_work", "viscous_dissipation",
                "volume_correction_energy", "total_energy", "boundary_work", "max_speed"},
               {}));

class FluidProbe final : public Probe {
 public:
  FluidProbe(const FluidModel& m, std::string name, std::string type, Params p);
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  /// The distance from q to the segment a_-b_ (a point when a_ = b_).
  double segment_distance(const Vec2& q) const {
    const Vec2 d = b_ - a_;
    const double t = d.squaredNorm() > 0 ? std::clamp((q - a_).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (q - (a_ + t * d)).norm();
  }
  const FluidModel& m_;
  std::string name_, type_;
  Vec2 a_ = Vec2::Zero(), b_ = Vec2::Zero();
  double band_ = 0, coord_ = 0;
  bool mesh_method_ = true;
  bool load_method_ = false;  // pressure: from the walls' loads
  /// The load sensor's reading (method "load").
  double wall_load_pressure() const;
  int component_ = 0;
  int wall_ = -1;  // wall_force: the wall's index
  /// The discharge through a_-b_ (the part of it in each element, where u is linear: its midpoint's u.n).
  double discharge() const;
  /// The P1 interpolation at a_ of the nodal values value(i) in the first element that holds a_ (its barycentric
  /// coordinates at least -tol), or `outside` when none does.
  template <class Value>
  double interpolated_at(double tol, double outside, Value value) const {
    for (const auto& t : m_.triangles()) {
      const Vec2 p[3] = {m_.pos(t[0]), m_.pos(t[1]), m_.pos(t[2])};
      const double area2 = cross(p[1] - p[0], p[2] - p[0]);
      if (!(std::abs(area2) > 0)) continue;
      double w[3];
      bool in = true;
      for (int k = 0; k < 3; ++k) {
        w[k] = cross(p[(k + 1) % 3] - a_, p[(k + 2) % 3] - a_) / area2;
        in = in && w[k] >= -tol;
      }
      if (!in) continue;
      double v = 0;
      for (int k = 0; k < 3; ++k) v += w[k] * value(t[k]);
      return v;
    }
    return outside;
  }
};

}  // namespace

std::unique_ptr<Probe> make_fluid_probe(const FluidModel& m, std::string name, std::string type, Params p) {
  return std::make_unique<FluidProbe>(m, std::move(name), std::move(type), std::move(p));
}

FluidProbe::FluidProbe(const FluidModel& m, std::string name, std::string type, Params p)
    : m_(m), name_(std::move(name)), type_(std::move(type)) {
  const double h = m.spacing();
  // Where there is something to measure: the particles' extent (fluid and walls) at the start and the walls'
  // polylines (without wall particles: "wall_model": "constraints"), plus h. A probe outside it is a typing
  // error (x of another case, a flipped sign) that would write nan or 0 for ever.
  Vec2 lo, hi;
  m.walls_box(lo, hi);
  for (Index i = 0; i < m.n(); ++i) {
    lo = lo.cwiseMin(m.pos(i));
    hi = hi.cwiseMax(m.pos(i));
  }
  lo -= Vec2::Constant(h);
  hi += Vec2::Constant(h);
  // A band narrower than a quarter of the spacing sees no particle (a nan for ever).
  auto read_band = [&] {
    band_ = p.positive("band");
    if (band_ < 0.25 * h) p.fail("band", "narrower than a quarter of the particle spacing: it would see no particle");
  };
  auto inside = [&](const std::string& key, double v, int axis) {
    if (!(v >= lo[axis] && v <= hi[axis]))
      p.fail(key, "lies outside the fluid and its walls (" + std::string(axis ? "y" : "x") + " from " +
                      std::to_string(lo[axis] + h) + " to " + std::to_string(hi[axis] - h) + ")");
  };
  // A segment's ends ("from", "to"; the pressure sensor, the wall of a run-up).
  auto read_segment = [&] {
    a_ = p.vec2("from");
    b_ = p.vec2("to");
    for (int axis = 0; axis < 2; ++axis) {
      inside("from", a_[axis], axis);
      inside("to", b_[axis], axis);
    }
  };
  if (type_ == "front") {
    // largest x of fluid within a band above the floor
    p.validate(kFrontKeys, {{"band", 2.0 * h}});
    coord_ = p.number("floor");
    inside("floor", coord_, 1);
    read_band();
  } else if (type_ == "column_height") {
    // largest y of fluid within a band next to the left wall
    p.validate(kColumnHeightKeys, {{"band", 2.0 * h}});
    coord_ = p.number("wall");
    inside("wall", coord_, 0);
    read_band();
  } else if (type_ == "elevation") {
    // "mesh": the highest point of the meshed fluid on the vertical line x (free-surface edges
    // interpolated); "particles": the highest fluid particle within `band` of x (biased upwards by the
    // particle noise of the surface, kept for comparison).
    p.validate(kElevationKeys, {{"band", 1.5 * h}});
    coord_ = p.number("x");
    inside("x", coord_, 0);
    read_band();
    mesh_method_ = p.choice("method", {"mesh", "particles"}) == "mesh";
  } else if (type_ == "runup") {
    p.validate(kRunupKeys, {{"band", 1.5 * h}});
    read_segment();
    read_band();
  } else if (type_ == "water_above") {
    p.validate(kWaterAboveKeys);
    coord_ = p.number("level");
  } else if (type_ == "discharge") {
    p.validate(kDischargeKeys);
    read_segment();
    if (!((b_ - a_).norm() > 0)) p.fail("to", "the segment's two ends coincide");
  } else if (type_ == "velocity") {
    p.validate(kVelocityKeys);
    a_ = p.vec2("at");
    inside("at", a_.x(), 0);
    inside("at", a_.y(), 1);
    component_ = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
  } else if (type_ == "wall_force") {
    p.validate(kWallForceKeys);
    const std::string wall = p.string("wall");
    wall_ = m.wall_index(wall);
    if (wall_ < 0) p.fail("wall", "the body has no wall named '" + wall + "'");
    component_ = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
  } else if (type_ == "pressure") {
    p.validate(kPressureKeys, {{"tolerance", 0.5 * h}});
    read_segment();
    band_ = p.positive("tolerance");
    load_method_ = p.choice("method", {"particles", "load"}) == "load";
    if (load_method_) {
      if (!((b_ - a_).norm() > 0)) p.fail("to", "a load sensor needs a segment (its two ends coincide)");
      double distance = 0;
      m.wall_normal_near(0.5 * (a_ + b_), distance);
      if (!(distance <= band_))
        p.fail("from", "a load sensor lies on a wall: its segment's midpoint is " + std::to_string(distance) +
                           " m from the nearest wall, beyond its tolerance " + std::to_string(band_) + " m");
    }
  } else {
    p.validate(kGlobalKeys);
  }
}

std::vector<double> FluidProbe::sample() const {
  const Index n = m_.n();
  if (type_ == "fluid_area") return {m_.area_end()};
  if (type_ == "water_area") return {m_.water_area()};
  if (type_ == "kinetic_energy") return {m_.kinetic_energy()};
  if (type_ == "potential_energy") return {m_.potential_energy()};
  if (type_ == "gravity_work") return {m_.gravity_work()};
  if (type_ == "viscous_dissipation") return {m_.viscous_dissipation()};
  if (type_ == "volume_correction_energy") return {m_.correction_energy()};
  if (type_ == "total_energy") return {m_.total_energy()};
  if (type_ == "boundary_work") return {m_.boundary_work()};
  if (type_ == "max_speed") {
    double v = 0;
    for (Index i = 0; i < n; ++i)
      if (m_.is_fluid(i)) v = std::max(v, m_.vel(i).norm());
    return {v};
  }
  if (type_ == "discharge") return {discharge()};
  if (type_ == "velocity")  // component component_ of the velocity at a_, nan outside the fluid
    return {interpolated_at(1e-12, std::numeric_limits<double>::quiet_NaN(),
                            [&](Index i) { return m_.vel(i)[component_]; })};
  if (type_ == "wall_force") return {m_.wall_force(wall_)[component_]};
  if (type_ == "water_above") {
    Index above = 0, fluid = 0;
    for (Index i = 0; i < n; ++i) {
      if (!m_.is_fluid(i)) continue;
      ++fluid;
      if (m_.pos(i).y() > coord_) ++above;
    }
    return {fluid ? static_cast<double>(above) / static_cast<double>(fluid) : 0.0};
  }
  if (type_ == "runup") {
    double top = std::numeric_limits<double>::quiet_NaN();
    for (Index i = 0; i < n; ++i) {
      if (!m_.is_fluid(i) || !m_.is_connected(i)) continue;
      const Vec2 q = m_.pos(i);
      if (segment_distance(q) <= band_ && !(q.y() <= top)) top = q.y();
    }
    return {top};
  }
  if (type_ == "pressure" && (b_ - a_).norm() == 0.0) {
    // A point sensor: the P1 pressure of the element that holds the point (within round-off of its edges, so a
    // point on a wall is held), 0 when none does (a dry sensor).
    return {interpolated_at(1e-9, 0.0, [&](Index i) { return m_.pressure(i); })};
  }
  if (type_ == "pressure" && load_method_) return {wall_load_pressure()};
  if (type_ == "pressure") {
    // mean pressure of the particles on the sensor segment (any kind)
    double s = 0;
    int count = 0;
    for (Index i = 0; i < n; ++i) {
      if (segment_distance(m_.pos(i)) <= band_ && m_.is_connected(i)) {
        s += m_.pressure(i);
        ++count;
      }
    }
    return {count ? s / count : 0.0};
  }
  double best = -std::numeric_limits<double>::infinity();
  if (type_ == "elevation" && mesh_method_) {
    for (const auto& t : m_.triangles())
      for (int k = 0; k < 3; ++k) {
        const Vec2 a = m_.pos(t[k]), b = m_.pos(t[(k + 1) % 3]);
        const double da = a.x() - coord_, db = b.x() - coord_;
        if (da * db > 0) continue;
        best = std::max(best, da == db ? std::max(a.y(), b.y()) : a.y() + (b.y() - a.y()) * da / (da - db));
      }
    return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
  }
  for (Index i = 0; i < n; ++i) {
    if (!m_.is_fluid(i) || !m_.is_connected(i)) continue;
    const Vec2 q = m_.pos(i);
    if (type_ == "front" && q.y() <= coord_ + band_) best = std::max(best, q.x());
    if (type_ == "column_height" && q.x() <= coord_ + band_) best = std::max(best, q.y());
    if (type_ == "elevation" && std::abs(q.x() - coord_) <= band_) best = std::max(best, q.y());
  }
  return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
}

double FluidProbe::wall_load_pressure() const {
  // The particles the walls hold along the sensor's line, in order along it (s: the distance from `from`), within
  // the tolerance of the line and two spacings beyond the segment's ends (their shares reach into it).
  const Vec2 d = b_ - a_;
  const double length = d.norm();
  const Vec2 e = d / length;
  const double reach = 2.0 * m_.spacing();
  struct Held {
    double s;
    Vec2 force;
  };
  std::vector<Held> held;
  for (const FluidModel::WallLoad& w : m_.wall_loads()) {
    const double s = (w.at - a_).dot(e);
    if (s < -reach || s > length + reach || std::abs(cross(e, w.at - a_)) > band_) continue;
    held.push_back({s, w.force});
  }
  if (held.empty()) return 0.0;
  std::sort(held.begin(), held.end(), [](const Held& p, const Held& q) { return p.s < q.s; });
  // Each particle stands for the wall from half-way to its previous neighbour to half-way to its next (the first
  // and last as far out as in): its force counts with the part of that share that lies on the segment.
  Vec2 force = Vec2::Zero();
  const size_t n = held.size();
  for (size_t k = 0; k < n; ++k) {
    const double before =
        k > 0 ? 0.5 * (held[k].s - held[k - 1].s) : (n > 1 ? 0.5 * (held[1].s - held[0].s) : 0.5 * m_.spacing());
    const double after = k + 1 < n ? 0.5 * (held[k + 1].s - held[k].s) : before;
    const double lo = held[k].s - before, hi = held[k].s + after;
    if (!(hi > lo)) continue;
    const double on = std::max(0.0, std::min(hi, length) - std::max(lo, 0.0));
    force += (on / (hi - lo)) * held[k].force;
  }
  // Positive when the fluid pushes on the wall: along the wall's normal away from the fluid.
  double distance = 0;
  const Vec2 toward_fluid = m_.wall_normal_near(0.5 * (a_ + b_), distance);
  const double p = -toward_fluid.dot(force) / length;
  return p == 0.0 ? 0.0 : p;  // no -0 in probes.csv
}

double FluidProbe::discharge() const {
  const Vec2 d = b_ - a_;
  const double length = d.norm();
  const Vec2 n = Vec2(d.y(), -d.x()) / length;
  double q = 0;
  for (const auto& t : m_.triangles()) {
    const Vec2 p[3] = {m_.pos(t[0]), m_.pos(t[1]), m_.pos(t[2])};
    const double area2 = cross(p[1] - p[0], p[2] - p[0]);
    if (!(std::abs(area2) > 0)) continue;
    // The segment's parameters s in [0, 1] inside the triangle: each edge's half-plane clips [lo, hi].
    double lo = 0, hi = 1;
    for (int k = 0; k < 3 && lo < hi; ++k) {
      const Vec2 e0 = p[k], e1 = p[(k + 1) % 3];
      // Inside: sign(area2) * cross(e1 - e0, x - e0) >= 0, linear in s: f(s) = f0 + s df.
      const double f0 = area2 * cross(e1 - e0, a_ - e0), df = area2 * cross(e1 - e0, d);
      if (df == 0) {
        if (f0 < 0) hi = lo;
      } else if (df > 0) {
        lo = std::max(lo, -f0 / df);
      } else {
        hi = std::min(hi, -f0 / df);
      }
    }
    if (!(hi > lo)) continue;
    const Vec2 mid = a_ + 0.5 * (lo + hi) * d;
    // P1 interpolation of the velocity at the chord's midpoint (barycentric coordinates).
    Vec2 u = Vec2::Zero();
    for (int k = 0; k < 3; ++k) u += cross(p[(k + 1) % 3] - mid, p[(k + 2) % 3] - mid) / area2 * m_.vel(t[k]);
    q += (hi - lo) * length * u.dot(n);
  }
  return q;
}

}  // namespace lagfsi::fluid
