// A wall segment that prescribes the velocity of the fluid particles on it: a lid moving in its own plane (the
// lid-driven cavity), a belt, a wall sliding along itself. Both components of every fluid particle within
// `tolerance` h of the segment at the start of a step follow
//   x(t) = x(t_n) + U (F(t) - F(t_n)),   v(t) = U f(t),   a(t) = U f'(t),
// over the step, with U the case's "velocity" and f its time function ("function", F its integral; f = 1 without
// one, or {}): an exact no-slip condition on a moving surface. A particle a wall already holds keeps the wall's
// condition. The segment itself does not move.
#include "fluid_boundary.hpp"

#include <lagfsi/geometry2d.hpp>

#include <algorithm>

namespace lagfsi::fluid {

namespace {

const KeyTable kPrescribedVelocityKeys(
    "/bodies/*/boundaries/* (fluid body, type prescribed_velocity)",
    "A segment that moves the fluid particles on it at a given velocity (a lid, a belt); the segment does not move.",
    {{"type", "prescribed_velocity", "`prescribed_velocity`."},
     {"name", "boundary", "Boundary name (summary.json); default: boundary<index>.", kDerived},
     {"segment", nullptr, "The segment [[x0, y0], [x1, y1]] (m)."},
     {"velocity", nullptr, "The velocity [u, v] (m/s) of the particles on it, scaled by the function."},
     {"function", Json::object(),
      "A time function f(t) scaling the velocity (see time function (type ...)); default {}: 1."},
     {"tolerance", 1e-6, "A fluid particle within this times h of the segment is on it."}});

class PrescribedVelocity final : public FluidBoundary {
 public:
  PrescribedVelocity(Params p, const BoundaryContext& ctx) {
    p.validate(kPrescribedVelocityKeys, {{"name", ctx.name}});
    const BoundarySegment seg(p, 1e-6 * ctx.h, "the two points coincide");
    a_ = seg.a;
    b_ = seg.b();
    u_ = p.vec2("velocity");
    fn_ = BoundaryFunction(p, ctx.base_dir);
    tol_ = p.non_negative("tolerance") * ctx.h;
  }

  void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                 std::vector<BoundaryConstraint>& out) override {
    t0_ = t;
    held_ = 0;
    const Vec& x = cloud.x();
    for (Index i = 0; i < cloud.n(); ++i) {
      if (!cloud.is_fluid(i) || taken[static_cast<size_t>(i)]) continue;
      const Vec2 p = x.segment<2>(2 * i);
      if (segment_distance(p, a_, b_) > tol_) continue;
      out.push_back({i, 0, p.x()});
      out.push_back({i, 1, p.y()});
      ++held_;
    }
    held_max_ = std::max(held_max_, held_);
  }
  double position(const BoundaryConstraint& k, double t) const override {
    return k.base + u_[k.c] * (fn_.integral(t) - fn_.integral(t0_));
  }
  double velocity(const BoundaryConstraint& k, double t) const override { return u_[k.c] * fn_.value(t); }
  double acceleration(const BoundaryConstraint& k, double t) const override { return u_[k.c] * fn_.rate(t); }
  Json summary() const override { return {{"type", "prescribed_velocity"}, {"particles_held_max", held_max_}}; }
  void serialize(StateArchive& ar) override { ar.io(t0_, held_, held_max_); }

 private:
  Vec2 a_, b_, u_;
  BoundaryFunction fn_;
  double tol_ = 0, t0_ = 0;
  long held_ = 0, held_max_ = 0;
};

}  // namespace

std::unique_ptr<FluidBoundary> make_prescribed_velocity_boundary(Params p, const BoundaryContext& ctx) {
  return std::make_unique<PrescribedVelocity>(std::move(p), ctx);
}

}  // namespace lagfsi::fluid
