#pragma once
/// @file fluid_boundary.hpp (private to src/fluid)
/// A boundary condition of the fluid as a process with step hooks, in the spirit of Kratos' processes: a boundary
/// chosen in the case file (/bodies/i/boundaries/j, by its "type"; fluid_boundaries.cpp keeps the registry) finds
/// the fluid particles it holds at the start of every step, prescribes components of their motion, and may act
/// on the particles after the step. The schemes see every boundary's prescribed components through
/// FluidBoundaries (fluid_boundaries.hpp), the walls' first: a component prescribed as x_c(t) enters the
/// monolithic scheme as a Dirichlet condition on the position, the fractional step's predictor as one on the
/// velocity dx_c/dt. Open boundaries (an inflow, an outflow) also add particles after a step, take particles at the
/// remesh, add the region they fill to the advected domain and keep the pressure of the particles they hold
/// unknown (not free surface).
#include <lagfsi/fluid/particle_cloud.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/time_function.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::fluid {

/// A prescribed component: component c (0: x, 1: y) of particle i, at `base` when the step started.
struct BoundaryConstraint {
  Index i;
  int c;
  double base;
};

/// A boundary's segment ("segment": [[x0, y0], [x1, y1]]): its start a, unit tangent t (towards the end), the unit
/// normal n = perp(t) (to the left of t) and its length. Shorter than `min_length`: an error at the key.
struct BoundarySegment {
  Vec2 a = Vec2::Zero(), tangent = Vec2::UnitX(), normal = Vec2::UnitY();
  double length = 0;
  BoundarySegment() = default;
  BoundarySegment(Params& p, double min_length, const std::string& too_short);
  Vec2 b() const { return a + tangent * length; }
};

/// A boundary's optional time function ("function": {} or absent: f = 1): f, its integral from 0 and its rate (a
/// central difference, as for the walls' motions).
class BoundaryFunction {
 public:
  BoundaryFunction() = default;
  BoundaryFunction(Params& p, const std::filesystem::path& base_dir);
  double value(double t) const { return fn_ ? fn_->value(t) : 1.0; }
  double integral(double t) const { return fn_ ? fn_->integral(t) : t; }
  double rate(double t) const;

 private:
  std::shared_ptr<TimeFunction> fn_;
};

/// What a boundary is built with.
struct BoundaryContext {
  double h = 0;                    ///< the particle spacing
  std::filesystem::path base_dir;  ///< the case file's folder (tables of time functions)
  std::string name;                ///< its default name: boundary<index>
};

class FluidBoundary {
 public:
  virtual ~FluidBoundary() = default;
  /// At the start of a step (after remeshing; t the step's start, x the particles' positions): appends the
  /// components it prescribes over the step. `taken` (per particle) marks those a wall already holds: a
  /// boundary leaves them to the wall.
  virtual void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                         std::vector<BoundaryConstraint>& out) = 0;
  /// The prescribed position, velocity and acceleration of one of its components at time t.
  virtual double position(const BoundaryConstraint& k, double t) const = 0;
  virtual double velocity(const BoundaryConstraint& k, double t) const = 0;
  virtual double acceleration(const BoundaryConstraint& k, double t) const = 0;
  /// After the step converged (x_start: the positions at its start; t its end): acts on the particles
  /// (injects, puts back; a particle is only appended here, never removed: the step's mesh still refers to the
  /// cloud). Returns the area of the fluid it added (an inflow). None by default.
  virtual double after_step(ParticleCloud& cloud, const Vec& x_start, double t) {
    (void)cloud;
    (void)x_start;
    (void)t;
    return 0.0;
  }
  /// An outflow: whether the fluid particle at x has left through it (it is removed at the next remesh with the
  /// elements it belongs to; `left` then receives their number and area). None by default.
  virtual bool takes(const Vec2& x) const {
    (void)x;
    return false;
  }
  virtual void left(long particles, double area) {
    (void)particles;
    (void)area;
  }
  /// An outflow: a particle on the mesh's boundary at x takes p = 0 exactly, whatever the free surface's condition
  /// (a weak one leaves a confined flow's pressure level floating). None by default.
  virtual bool zero_pressure(const Vec2& x) const {
    (void)x;
    return false;
  }
  /// Water enters or leaves through it (an inflow, an outflow).
  virtual bool open() const { return false; }
  /// The particles it holds keep their pressure unknown and their continuity equation: they are not free surface
  /// though they lie on the mesh's boundary (an inflow's layer carries the pressure of the flow behind it).
  virtual bool holds_pressure() const { return false; }
  /// Triangles the advected and level-set detections count as fluid besides the last step's mesh (the strip an
  /// inflow fills with its new particles). None by default.
  virtual void fluid_regions(std::vector<std::array<Vec2, 3>>& out) const { (void)out; }
  /// Its numbers for summary.json (an object under the boundary's name; empty: none).
  virtual Json summary() const { return Json::object(); }
  /// Checkpoints: what it keeps from step to step.
  virtual void serialize(StateArchive& ar) { (void)ar; }
};

}  // namespace lagfsi::fluid
