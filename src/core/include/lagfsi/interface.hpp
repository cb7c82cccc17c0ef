#pragma once
/// @file interface.hpp
/// What a body offers to a partitioned coupling (fsi/), beside the PhysicsModel lifecycle. The coupling
/// sees only these two interfaces, never the physics behind them:
///
///  - a structure (Neumann side) gives its wet boundary (nodes and edges, built from a case-file
///    selection), takes interface forces on those nodes, re-solves its step from the predicted state, and
///    reports its interface positions, velocities and accelerations;
///  - a fluid (Dirichlet side) carries ghost particles that follow the structure's boundary (they join its
///    remeshing, and a fluid element that uses one means contact), takes their prescribed motion for the
///    step, re-solves its step, and reports the forces it exerts on them.
///
/// Forces on the interface are consistent nodal forces: the fluid's are the reactions at the ghost
/// particles' prescribed momentum rows (the force the wall must apply to hold them, with the sign flipped),
/// so the forces on the structure are equal and opposite to those on the fluid by construction.
#include <lagfsi/params.hpp>
#include <lagfsi/types.hpp>

#include <string>
#include <utility>
#include <vector>

namespace lagfsi {

/// A wet boundary of a structure: its points (sorted ids of the structure's surface points — a continuum's
/// node ids, a shell's face points, see StructuralBody in solid.hpp) and its boundary edges as order+1 point
/// lists (from the first vertex to the second, the interior points in between).
struct InterfaceBoundary {
  std::vector<Index> nodes;
  std::vector<std::vector<Index>> edges;
  std::vector<Vec2> reference;  ///< reference positions of `nodes`
};

class InterfaceStructure {
 public:
  virtual ~InterfaceStructure() = default;
  /// The boundary edges whose nodes are all selected by `select` (select_nodes syntax); throws InputError
  /// at `select` when the selection contains no boundary edge.
  virtual InterfaceBoundary make_interface(Params select) const = 0;
  /// Interface forces for the step being solved (2 per node of `nodes`, global ids); they replace the last
  /// ones given.
  virtual void set_interface_forces(const std::vector<Index>& nodes, const Vec& forces) = 0;
  /// Back to the step's predicted state (after predict(); the state at t_n is untouched).
  virtual void restart_step() = 0;
  /// Augmented mass (Tezduyar 2004): adds (factor - 1) c_m M (x - x_prev) to the residual and
  /// (factor - 1) c_m M to the tangent, x_prev the positions of the last coupling iterate. It vanishes when
  /// the coupling converges (the converged step is unchanged) and damps the iterate's motion. 1 = off.
  virtual void set_augmented_mass(double factor) = 0;
  /// Positions, velocities and accelerations at t_{n+1} of `nodes` (2 per node) for interface positions
  /// `x` of those nodes (the other dofs at the current iterate), from the time integrator's update.
  virtual void interface_kinematics(const std::vector<Index>& nodes, const Vec& x, Vec& v, Vec& a) const = 0;
  /// Positions of `nodes` at the current iterate (after the last solve).
  virtual Vec interface_positions(const std::vector<Index>& nodes) const = 0;
  /// Positions of `nodes` at the start of the step (t_n).
  virtual Vec interface_positions_old(const std::vector<Index>& nodes) const = 0;
};

class InterfaceFluid {
 public:
  virtual ~InterfaceFluid() = default;
  /// Adds ghost particles at `points` (called before initialize()). `adjacent` lists pairs of ghost
  /// indices (into `points`) that are neighbours along the structure's boundary: an element with two ghost
  /// particles that are not neighbours crosses the structure and is removed. A ghost that coincides with a
  /// wall particle (within h/4: a clamped corner) is that particle: it stays fixed and its force is not
  /// transmitted (the structure must hold that node fixed).
  /// Fluid particles closer than h/2 to a ghost are dropped. Returns the number of ghosts merged with walls;
  /// throws std::invalid_argument when the fluid cannot carry ghosts.
  virtual int add_ghosts(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent) = 0;
  /// Whether a fluid element of the step's mesh uses a ghost particle (after predict()).
  virtual bool in_contact() const = 0;
  /// Motion of the ghost particles at t_{n+1} (2 per ghost each), used by the next solve.
  virtual void set_ghost_motion(const Vec& x, const Vec& v, const Vec& a) = 0;
  /// Back to the step's state right after predict() (the remeshed cloud at t_n), keeping the ghost motion.
  virtual void restart_step() = 0;
  /// Forces the fluid exerts on the ghost particles (2 per ghost) at the last solve.
  virtual Vec ghost_forces() const = 0;
};

}  // namespace lagfsi
