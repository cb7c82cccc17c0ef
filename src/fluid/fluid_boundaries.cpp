#include "fluid_boundaries.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <string>

namespace lagfsi::fluid {

// The builders of the boundary types (fluid_boundaries.def), each defined in its own file.
#define LAGFSI_FLUID_BOUNDARY(type) \
  std::unique_ptr<FluidBoundary> make_##type##_boundary(Params, const BoundaryContext&);
#include "fluid_boundaries.def"
#undef LAGFSI_FLUID_BOUNDARY

BoundarySegment::BoundarySegment(Params& p, double min_length, const std::string& too_short) {
  const std::vector<Vec2> s = p.points("segment");
  if (s.size() != 2) p.fail("segment", "expected two points [[x0, y0], [x1, y1]]");
  a = s[0];
  const Vec2 e = s[1] - s[0];
  length = e.norm();
  if (!(length > min_length)) p.fail("segment", too_short);
  tangent = e / length;
  normal = Vec2(-tangent.y(), tangent.x());
}

BoundaryFunction::BoundaryFunction(Params& p, const std::filesystem::path& base_dir) {
  if (!p.json().at("function").empty()) fn_ = make_time_function(p.at("function"), base_dir);
}

double BoundaryFunction::rate(double t) const {
  if (!fn_) return 0.0;
  const double d = 1e-4;
  return (fn_->value(t + d) - fn_->value(t - d)) / (2 * d);
}

namespace {
using BoundaryBuilder = std::function<std::unique_ptr<FluidBoundary>(Params, const BoundaryContext&)>;
const std::map<std::string, BoundaryBuilder>& boundary_registry() {
  static const std::map<std::string, BoundaryBuilder> r = {
#define LAGFSI_FLUID_BOUNDARY(type) {#type, make_##type##_boundary},
#include "fluid_boundaries.def"
#undef LAGFSI_FLUID_BOUNDARY
  };
  return r;
}
}  // namespace

void FluidBoundaries::read(Params boundaries, const BoundaryContext& ctx) {
  if (!boundaries.json().is_array()) boundaries.fail("expected an array of boundaries");
  std::vector<std::string> types;
  for (const auto& [k, v] : boundary_registry()) types.push_back(k);
  for (size_t j = 0; j < boundaries.size(); ++j) {
    Params b = boundaries.at(j);
    if (!b.json().is_object()) b.fail("expected an object");
    if (!b.has("type")) b.fail("type", "required key is missing");
    const std::string type = b.choice("type", types);
    BoundaryContext bc = ctx;
    bc.name = "boundary" + std::to_string(j);
    boundaries_.push_back(boundary_registry().at(type)(b, bc));
    const std::string name = b.identifier("name");
    for (const auto& n : names_)
      if (n == name) b.fail("name", "duplicate boundary name '" + name + "'");
    names_.push_back(name);
  }
}

void FluidBoundaries::update(const ParticleCloud& cloud, double t) {
  all_ = walls_.constraints();
  if (boundaries_.empty()) return;
  const std::vector<char> taken = walls_.on_wall(cloud.n());
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    scratch_.clear();
    boundaries_[b]->constrain(cloud, taken, t, scratch_);
    for (const BoundaryConstraint& k : scratch_) {
      WallConstraint w{k.i, k.c, k.base, -1};
      w.boundary = static_cast<int>(b) + 1;
      all_.push_back(w);
    }
  }
}

namespace {
BoundaryConstraint own(const WallConstraint& k) { return {k.i, k.c, k.base}; }
}  // namespace

double FluidBoundaries::position(const WallConstraint& k, double t) const {
  return k.boundary == 0 ? walls_.constraint_position(k, t)
                         : boundaries_[static_cast<size_t>(k.boundary - 1)]->position(own(k), t);
}

double FluidBoundaries::velocity(const WallConstraint& k, double t) const {
  return k.boundary == 0 ? walls_.constraint_velocity(k, t)
                         : boundaries_[static_cast<size_t>(k.boundary - 1)]->velocity(own(k), t);
}

std::vector<char> FluidBoundaries::on_wall(Index n) const {
  std::vector<char> on = walls_.on_wall(n);
  for (const WallConstraint& k : all_)
    if (k.boundary > 0 && k.i < n) ++on[static_cast<size_t>(k.i)];
  return on;
}

void FluidBoundaries::place(double t, const Vec& X0, Vec& x) const {
  walls_.place(t, X0, x);
  for (const WallConstraint& k : all_)
    if (k.boundary > 0) x[2 * k.i + k.c] = position(k, t);
}

void FluidBoundaries::set_motion(double t, Vec& v, Vec& a) const {
  walls_.set_wall_motion(t, v, a);
  for (const WallConstraint& k : all_)
    if (k.boundary > 0) {
      const FluidBoundary& b = *boundaries_[static_cast<size_t>(k.boundary - 1)];
      v[2 * k.i + k.c] = b.velocity(own(k), t);
      a[2 * k.i + k.c] = b.acceleration(own(k), t);
    }
}

double FluidBoundaries::after_step(ParticleCloud& cloud, const Vec& x_start, double t) {
  double added = 0.0;
  for (auto& b : boundaries_) added += b->after_step(cloud, x_start, t);
  return added;
}

bool FluidBoundaries::open() const {
  return std::any_of(boundaries_.begin(), boundaries_.end(), [](const auto& b) { return b->open(); });
}

int FluidBoundaries::taker(const Vec2& x) const {
  for (size_t b = 0; b < boundaries_.size(); ++b)
    if (boundaries_[b]->takes(x)) return static_cast<int>(b);
  return -1;
}

void FluidBoundaries::clear_free_surface(std::vector<std::uint8_t>& free) const {
  for (const WallConstraint& k : all_)
    if (k.boundary > 0 && boundaries_[static_cast<size_t>(k.boundary - 1)]->holds_pressure() &&
        static_cast<size_t>(k.i) < free.size())
      free[static_cast<size_t>(k.i)] = 0;
}

void FluidBoundaries::fix_outlet_pressure(const ParticleCloud& cloud, const std::vector<std::uint8_t>& free,
                                          std::vector<char>& fixed) const {
  for (const auto& b : boundaries_)
    if (b->open())
      for (Index i = 0; i < cloud.n(); ++i)
        if (cloud.is_fluid(i) && free[static_cast<size_t>(i)] && b->zero_pressure(cloud.pos(i))) fixed[3 * i + 2] = 1;
}

std::vector<std::array<Vec2, 3>> FluidBoundaries::fluid_regions() const {
  std::vector<std::array<Vec2, 3>> out;
  for (const auto& b : boundaries_) b->fluid_regions(out);
  return out;
}

Json FluidBoundaries::summary() const {
  Json s = Json::object();
  for (size_t b = 0; b < boundaries_.size(); ++b) s[names_[b]] = boundaries_[b]->summary();
  return s;
}

void FluidBoundaries::serialize(StateArchive& ar) {
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    ar.section("boundary " + names_[b]);
    boundaries_[b]->serialize(ar);
  }
}

}  // namespace lagfsi::fluid
