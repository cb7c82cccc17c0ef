#include "fluid_boundaries.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <stdexcept>
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

void FluidBoundaries::set_walls(std::unique_ptr<FluidWalls> walls) {
  if (!list_.empty()) throw std::logic_error("FluidBoundaries: the walls come first");
  walls_ = walls.get();
  list_.push_back(std::move(walls));
}

void FluidBoundaries::read(Params boundaries, const BoundaryContext& ctx) {
  if (!walls_) throw std::logic_error("FluidBoundaries: the walls come first");
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
    list_.push_back(boundary_registry().at(type)(b, bc));
    const std::string name = b.identifier("name");
    for (const auto& n : names_)
      if (n == name) b.fail("name", "duplicate boundary name '" + name + "'");
    names_.push_back(name);
  }
}

bool FluidBoundaries::finds_contacts() const {
  return std::any_of(list_.begin(), list_.end(), [](const auto& b) { return b->finds_contacts(); });
}

void FluidBoundaries::find(const ParticleCloud& cloud, double t) {
  for (auto& b : list_) b->find(cloud, t);
}

std::vector<char> FluidBoundaries::held(Index n) const {
  std::vector<char> on(static_cast<size_t>(n), 0);
  for (const auto& b : list_) b->count_held(on);
  return on;
}

bool FluidBoundaries::along(const Vec2& p) const {
  return std::any_of(list_.begin(), list_.end(), [&](const auto& b) { return b->along(p); });
}

bool FluidBoundaries::along_fixed(const Vec2& p) const {
  return std::any_of(list_.begin(), list_.end(), [&](const auto& b) { return b->along_fixed(p); });
}

void FluidBoundaries::settle(const std::vector<std::uint8_t>& free) {
  for (auto& b : list_) b->settle(free);
}

void FluidBoundaries::update(const ParticleCloud& cloud, double t) {
  all_.clear();
  frictions_.clear();
  first_.clear();
  std::vector<char> taken(static_cast<size_t>(cloud.n()), 0);
  for (size_t b = 0; b < list_.size(); ++b) {
    first_.push_back(all_.size());
    scratch_.clear();
    list_[b]->constrain(cloud, taken, t, scratch_);
    for (BoundaryConstraint k : scratch_) {
      k.boundary = static_cast<int>(b);
      all_.push_back(k);
    }
    const size_t nf = frictions_.size();
    list_[b]->frictions(frictions_);
    for (size_t f = nf; f < frictions_.size(); ++f) frictions_[f].boundary = static_cast<int>(b);
    for (size_t k = first_.back(); k < all_.size(); ++k)
      if (all_[k].i < cloud.n()) taken[static_cast<size_t>(all_[k].i)] = 1;
  }
  first_.push_back(all_.size());
}

std::vector<char> FluidBoundaries::on_wall(Index n) const {
  std::vector<char> on(static_cast<size_t>(n), 0);
  for (const BoundaryConstraint& k : all_)
    if (k.i < n) ++on[static_cast<size_t>(k.i)];
  return on;
}

void FluidBoundaries::place(double t, const Vec& X0, Vec& x) const {
  for (const auto& b : list_) b->place_own(t, X0, x);
  const ParticleFrames& f = frames();
  for (const BoundaryConstraint& k : all_) f.set_component(x, k.i, k.c, position(k, t));
}

void FluidBoundaries::set_motion(double t, Vec& v, Vec& a) const {
  // The prescribed components' velocities and accelerations, also on fixed walls (zero): a particle put on a wall
  // at the end of the last step arrives with its own velocity, which the constraint's first step would otherwise
  // reflect (the trapezoidal rule's v_{n+1} = 2 (x_{n+1} - x_n) / dt - v_n).
  move_own(t, v, a);
  const ParticleFrames& f = frames();
  for (const BoundaryConstraint& k : all_) {
    const FluidBoundary& b = *list_[index(k)];
    f.set_component(v, k.i, k.c, b.velocity(k, t));
    f.set_component(a, k.i, k.c, b.acceleration(k, t));
  }
}

bool FluidBoundaries::inviscid(const std::array<Index, 3>& t) const {
  return std::any_of(list_.begin(), list_.end(), [&](const auto& b) { return b->inviscid(t); });
}

double FluidBoundaries::after_step(ParticleCloud& cloud, const Vec& x_start, double t, const FluidMesh& mesh,
                                   const Vec& force) {
  const bool forces = static_cast<size_t>(force.size()) == all_.size() && first_.size() == list_.size() + 1;
  double added = 0.0;
  for (size_t b = 0; b < list_.size(); ++b) {
    const Vec own =
        forces ? Vec(force.segment(static_cast<Index>(first_[b]), static_cast<Index>(first_[b + 1] - first_[b])))
               : Vec();
    added += list_[b]->after_step({cloud, x_start, t, mesh, own});
  }
  return added;
}

bool FluidBoundaries::open() const {
  return std::any_of(list_.begin(), list_.end(), [](const auto& b) { return b->open(); });
}

int FluidBoundaries::taker(const Vec2& x) const {
  for (size_t b = 0; b < list_.size(); ++b)
    if (list_[b]->takes(x)) return static_cast<int>(b);
  return -1;
}

int FluidBoundaries::outlet_strip(const Vec2& x) const {
  for (size_t b = 0; b < list_.size(); ++b)
    if (list_[b]->in_outlet_strip(x)) return static_cast<int>(b);
  return -1;
}

void FluidBoundaries::clear_free_surface(std::vector<std::uint8_t>& free) const {
  for (const BoundaryConstraint& k : all_)
    if (list_[index(k)]->holds_pressure() && static_cast<size_t>(k.i) < free.size()) free[static_cast<size_t>(k.i)] = 0;
}

std::vector<int> FluidBoundaries::inlets(const ParticleCloud& cloud) const {
  std::vector<int> out(static_cast<size_t>(cloud.n()), -1);
  for (size_t b = 1; b < list_.size(); ++b)
    if (list_[b]->open())
      for (Index i = 0; i < cloud.n(); ++i)
        if (out[static_cast<size_t>(i)] < 0 && list_[b]->in_inlet(cloud.pos(i)))
          out[static_cast<size_t>(i)] = static_cast<int>(b) - 1;
  return out;
}

bool FluidBoundaries::at_open_face(const Vec2& x) const {
  return std::any_of(list_.begin(), list_.end(),
                     [&](const auto& b) { return b->open() && (b->in_inlet(x) || b->zero_pressure(x)); });
}

void FluidBoundaries::fix_outlet_pressure(const ParticleCloud& cloud, const std::vector<std::uint8_t>& free,
                                          std::vector<char>& fixed) const {
  for (const auto& b : list_)
    if (b->open())
      for (Index i = 0; i < cloud.n(); ++i)
        if (cloud.is_fluid(i) && free[static_cast<size_t>(i)] && b->zero_pressure(cloud.pos(i))) fixed[3 * i + 2] = 1;
}

std::vector<std::array<Vec2, 3>> FluidBoundaries::fluid_regions() const {
  std::vector<std::array<Vec2, 3>> out;
  for (const auto& b : list_) b->fluid_regions(out);
  return out;
}

Json FluidBoundaries::summary() const {
  Json s = Json::object();
  for (size_t b = 1; b < list_.size(); ++b) s[names_[b - 1]] = list_[b]->summary();
  return s;
}

void FluidBoundaries::serialize(StateArchive& ar) {
  for (size_t b = 0; b < list_.size(); ++b) {
    if (b > 0) ar.section("boundary " + names_[b - 1]);
    list_[b]->serialize(ar);
  }
}

}  // namespace lagfsi::fluid
