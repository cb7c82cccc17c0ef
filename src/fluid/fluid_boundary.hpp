#pragma once
/// @file fluid_boundary.hpp (private to src/fluid)
/// A boundary condition of the fluid as a process with step hooks, in the spirit of Kratos' processes: it finds
/// the particles it holds at the start of every step, prescribes components of their motion (constrain the step),
/// may add a friction and inviscid elements to the system, and may act on the particles after the step. The
/// rigid walls (/bodies/i/walls, fluid_walls.hpp: wall particles, contact constraints or a fixed mesh's nodes) are
/// implementations, and so is every boundary chosen in the case file (/bodies/i/boundaries/j, by its "type";
/// fluid_boundaries.cpp keeps the registry). The schemes see them all through FluidBoundaries
/// (fluid_boundaries.hpp), the walls first: a component prescribed as x_c(t) enters the monolithic scheme as a
/// Dirichlet condition on the position, the fractional step's predictor as one on the velocity dx_c/dt. Open
/// boundaries (an inflow, an outflow) also add particles after a step, take particles at the remesh, add the region
/// they fill to the advected domain and keep the pressure of the particles they hold unknown (not free surface).
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_mesh.hpp"
#include "particle_frames.hpp"

#include <lagfsi/params.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/time_function.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::fluid {

/// A prescribed component: component c (0: x, 1: y; n, t in the particle's frame on an inclined wall,
/// particle_frames.hpp) of particle i, at `base` when the step started. `part` is the boundary's own (a wall's index
/// among the walls); `side` (+1 / -1) the direction of a wall's fluid side along the component for the normal
/// component of a particle on a wall with one fluid side, 0 otherwise; `tangential` marks the tangential component
/// of a particle held on a no-slip wall; `boundary` whose it is (FluidBoundaries' index: 0 the walls); `anchor` the
/// point of a turning wall the component follows (in the wall's initial position).
struct BoundaryConstraint {
  Index i;
  int c;
  double base;
  int part = -1;
  int side = 0;
  bool tangential = false;
  int boundary = 0;
  Vec2 anchor = Vec2::Zero();
};

/// A component of a particle on a boundary that slides against a linear friction -k (v_c - w_c(t)), k and the
/// boundary's velocity w_c given by the boundary (the walls' Navier friction, fluid_walls.hpp); `part` and
/// `boundary` as for a constraint.
struct BoundaryFriction {
  Index i;
  int c;
  int part = -1;
  int boundary = 0;
};

/// What a boundary sees after a converged step: the cloud (positions and velocities at the step's end, which it
/// may change), the positions at the step's start, the step's end time, its mesh and the forces its own
/// constraints applied to the fluid (in the order it gave them; empty when the scheme did not compute them).
struct StepEnd {
  ParticleCloud& cloud;
  const Vec& x_start;
  double t;
  const FluidMesh& mesh;
  const Vec& force;
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

  // --- Finding what it holds. The walls come first (FluidBoundaries), and these three hooks are called on
  // every boundary before the free surface is marked; the other boundaries find their particles in constrain().

  /// Whether it holds the particles it finds lying on it at every step (the walls as constraints): the free surface
  /// is then marked again after find(), and the remesh keeps the particles it holds in place.
  virtual bool finds_contacts() const { return false; }
  /// At the start of a step, and before the remesh of a step: finds the particles it holds (the walls'
  /// contacts). None by default.
  virtual void find(const ParticleCloud& cloud, double t) {
    (void)cloud;
    (void)t;
  }
  /// Adds to `held` (per particle) how many components of each particle it found holds.
  virtual void count_held(std::vector<char>& held) const { (void)held; }
  /// Whether p lies along it (free-surface marking: an unshared edge between two held particles whose midpoint
  /// lies along a boundary is that boundary, not a free surface).
  virtual bool along(const Vec2& p) const {
    (void)p;
    return false;
  }
  /// Whether p lies along a part of it that does not move.
  virtual bool along_fixed(const Vec2& p) const {
    (void)p;
    return false;
  }
  /// After the free surface was marked (`free`, per particle): adjusts what it holds (a no-slip wall lets its
  /// contact line move).
  virtual void settle(const std::vector<std::uint8_t>& free) { (void)free; }

  // --- Constraining the step.

  /// At the start of a step (after remeshing; t the step's start, x the particles' positions): appends the
  /// components it prescribes over the step. `taken` (per particle) marks those a boundary before it holds
  /// already (the walls'): it leaves them alone.
  virtual void constrain(const ParticleCloud& cloud, const std::vector<char>& taken, double t,
                         std::vector<BoundaryConstraint>& out) = 0;
  /// The prescribed position, velocity and acceleration of one of its components at time t.
  virtual double position(const BoundaryConstraint& k, double t) const = 0;
  virtual double velocity(const BoundaryConstraint& k, double t) const = 0;
  virtual double acceleration(const BoundaryConstraint& k, double t) const = 0;
  /// Particles of its own (not fluid: a wall's particles) moved to their prescribed positions at time t (X0
  /// their initial ones), and their prescribed velocities and accelerations. None by default.
  virtual void place_own(double t, const Vec& X0, Vec& x) const {
    (void)t;
    (void)X0;
    (void)x;
  }
  virtual void move_own(double t, Vec& v, Vec& a) const {
    (void)t;
    (void)v;
    (void)a;
  }
  /// The frames of the particles it holds on inclined lines (particle_frames.hpp); none by default.
  virtual const ParticleFrames* frames() const { return nullptr; }

  // --- Adding to the system.

  /// Appends the step's components that slide against its friction (found with its constraints).
  virtual void frictions(std::vector<BoundaryFriction>& out) const { (void)out; }
  /// The friction coefficient k (N s/m per unit depth) and the boundary's velocity along a friction's component.
  virtual double friction_coefficient(const BoundaryFriction& f) const {
    (void)f;
    return 0.0;
  }
  virtual double friction_velocity(const BoundaryFriction& f, double t) const {
    (void)f;
    (void)t;
    return 0.0;
  }
  /// Whether element t carries no viscous stress (the first layer of elements along a free-slip wall of
  /// particles). No by default.
  virtual bool inviscid(const std::array<Index, 3>& t) const {
    (void)t;
    return false;
  }

  // --- Acting after the step.

  /// After the step converged: acts on the particles (puts back, releases, injects; a particle is only appended
  /// here, never removed: the step's mesh still refers to the cloud). Returns the area of the fluid it added (an
  /// inflow). None by default.
  virtual double after_step(const StepEnd& s) {
    (void)s;
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
  /// An outflow: whether x lies in its strip (within two spacings of its line on the fluid's side, or beyond it).
  /// What a remesh changes of the mesh's area there is the outflow's: the elements it took with a particle reach
  /// up to the particles behind it, and the next remesh fills part of that ragged end again (RemeshPipeline).
  virtual bool in_outlet_strip(const Vec2& x) const {
    (void)x;
    return false;
  }
  /// An outflow: a particle on the mesh's boundary at x takes p = 0 exactly, whatever the free surface's condition
  /// (a weak one leaves a confined flow's pressure level floating). None by default.
  virtual bool zero_pressure(const Vec2& x) const {
    (void)x;
    return false;
  }
  /// An inflow: whether x lies in its inlet layer (where it holds the fluid particles, and where the walls at its
  /// ends hold them). None by default.
  virtual bool in_inlet(const Vec2& x) const {
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
