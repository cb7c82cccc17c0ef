// An outflow: a segment through which water leaves the fluid. A fluid particle that has crossed the segment's line
// to the side away from the fluid, within the segment's extent (half a spacing beyond its ends), is removed at the
// next remesh, with the elements it belongs to (the volume correction's reference loses their area, and summary.json
// counts it here). Those elements reach up to the particles behind it, and the remesh fills part of the ragged end
// again: what a remesh changes of the area within two spacings of the outlet is counted here too, so that what the
// outflow reports is what the mesh lost through it (without it, Turek & Hron's channel gained some 3 % of its inflow
// at the outlet, out of the balance). The particles on the mesh's boundary within a spacing of the outlet take p = 0
// exactly (whatever the free surface's condition: a weak Robin one leaves a confined flow's pressure level floating): a
// traction-free outlet that sets the pressure level of a confined flow (the "do-nothing" condition up to the viscous
// normal stress, which vanishes for a fully developed flow; Heywood, Rannacher & Turek 1996).
//
// The fluid's side is found at the first step: the side of the segment where the fluid particles within two
// spacings of it lie.
#include "fluid_boundary.hpp"

#include <cmath>

namespace lagfsi::fluid {

namespace {

const KeyTable kOutflowKeys(
    "/bodies/*/boundaries/* (fluid body, type outflow)",
    "A segment through which water leaves: particles that cross it are removed, the outlet's pressure is the free "
    "surface's (zero). Needs remeshing.",
    {{"type", "outflow", "`outflow`."},
     {"name", "boundary", "Boundary name (summary.json); default: boundary<index>.", kDerived},
     {"segment", nullptr, "The outlet segment [[x0, y0], [x1, y1]] (m), on the edge of the fluid."}});

class Outflow final : public FluidBoundary {
 public:
  Outflow(Params p, const BoundaryContext& ctx) : h_(ctx.h) {
    p.validate(kOutflowKeys, {{"name", ctx.name}});
    seg_ = BoundarySegment(p, 0.5 * h_, "shorter than half a particle spacing");
  }

  bool open() const override { return true; }

  void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                 std::vector<BoundaryConstraint>& out) override {
    (void)taken;
    (void)t;
    (void)out;
    if (oriented_) return;
    // The outward normal points away from the fluid next to the segment.
    double side = 0;
    for (Index i = 0; i < cloud.n(); ++i) {
      if (!cloud.is_fluid(i)) continue;
      const Vec2 q = cloud.pos(i) - seg_.a;
      const double s = q.dot(seg_.tangent), d = q.dot(seg_.normal);
      if (s >= 0 && s <= seg_.length && std::abs(d) <= 2 * h_) side += d;
    }
    if (side > 0) seg_.normal = -seg_.normal;
    oriented_ = side != 0;
  }
  double position(const BoundaryConstraint& k, double t) const override {
    (void)t;
    return k.base;
  }
  double velocity(const BoundaryConstraint&, double) const override { return 0.0; }
  double acceleration(const BoundaryConstraint&, double) const override { return 0.0; }

  bool takes(const Vec2& x) const override { return beyond(x, 0.0); }
  bool zero_pressure(const Vec2& x) const override { return beyond(x, -h_); }
  bool in_outlet_strip(const Vec2& x) const override { return beyond(x, -2 * h_); }
  void left(long particles, double area) override {
    particles_left_ += particles;
    area_left_ += area;
  }

  Json summary() const override {
    return {{"type", "outflow"}, {"particles_left", particles_left_}, {"area_left", area_left_}};
  }
  void serialize(StateArchive& ar) override { ar.io(oriented_, seg_.normal, particles_left_, area_left_); }

 private:
  /// x lies further out than `depth` along the outward normal, within half a spacing of the segment's extent.
  bool beyond(const Vec2& x, double depth) const {
    if (!oriented_) return false;
    const Vec2 q = x - seg_.a;
    const double s = q.dot(seg_.tangent);
    return q.dot(seg_.normal) > depth && s >= -0.5 * h_ && s <= seg_.length + 0.5 * h_;
  }

  double h_;
  BoundarySegment seg_;  // the normal away from the fluid once oriented
  bool oriented_ = false;
  long particles_left_ = 0;
  double area_left_ = 0;
};

}  // namespace

std::unique_ptr<FluidBoundary> make_outflow_boundary(Params p, const BoundaryContext& ctx) {
  return std::make_unique<Outflow>(std::move(p), ctx);
}

}  // namespace lagfsi::fluid
