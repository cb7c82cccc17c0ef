#pragma once
/// @file dirichlet_neumann.hpp
/// A fluid and a structure coupled through ghost particles (docs/theory/fsi.md; Avancini 2018, ch. 7), as one composite
/// PhysicsModel that the driver steps like any body:
///
///  - set-up: the structure's wet boundary (a node selection) gets ghost particles in the fluid, either one
///    per boundary node (a matching interface, as in Avancini 2018) or along the boundary edges at a chosen
///    spacing (a non-matching interface). Ghost g sits at x_g = sum_a N_a(s_g) x_a over the nodes a of its
///    edge (1D Lagrange shape functions of the edge's order at its parameter s_g); the force F_g the fluid
///    exerts on it goes to the nodes as f_a = sum_g N_a(s_g) F_g (the transpose: consistent, and the total
///    force and its work are the same on both sides);
///  - each step: both bodies predict (the fluid remeshes with its ghosts). Without contact (no fluid
///    element uses a ghost) the structure is solved alone, then the fluid with the ghosts where the
///    structure went. With contact, the Dirichlet–Neumann loop of coupling.hpp runs on the interface node
///    positions: fluid with the ghosts prescribed (positions, and the velocities and accelerations the time
///    integrator gives them) -> ghost forces -> structure loaded by them -> its interface positions, until
///    |x~ - x| <= tolerance * |x~ - x_n|, accelerated as chosen ("constant", "aitken", "iqn_ils",
///    "iqn_imvj"), from the first guess x_n + (dt/dt_prev)(x_n - x_{n-1}) ("predictor": "extrapolation") or the
///    structure's positions under the last step's interface forces ("forces"). Each pass re-solves both bodies from the
///    step's start (the fluid keeps the step's mesh and factorizations). A loop that fails after its first pass is run
///    once more with the accelerator's memory cleared; a second failure goes to the driver (dt/2);
///  - optional augmented mass of the structure (interface.hpp), a consistent under-relaxation (with constant
///    relaxation only: with the other accelerators a pass would depend on the structure's previous iterate).
///
/// Case file: "couplings": [{"type": "dirichlet_neumann", "name": "fsi", "fluid": <body>, "structure": <body>,
/// "interface": <node selection>, "ghost_spacing": 0 (0: at the nodes), "acceleration": {...},
/// "max_iterations": 50, "tolerance": 1e-6, "reference_floor": 1e-9 (m, the smallest motion the residual
/// is compared with), "augmented_mass": 1, "predictor": "extrapolation" | "forces"}].
/// Probes of a coupling: {"type": "interface_force", "component": "x"|"y"} (total force of the fluid on the
/// structure) and {"type": "iterations"}.
#include <lagfsi/case.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/model.hpp>

#include <memory>

namespace lagfsi::fsi {

/// The ghost particles of a structure's wet boundary and the transfer between them and its nodes:
/// x_g = sum_a N_a(s_g) x_a (to_ghosts), f_a = sum_g N_a(s_g) F_g (to_nodes, the transpose). The shape
/// functions of an edge sum to one, so the total force is the same on both sides, and the transpose keeps
/// the work: f_nodes . x_nodes = F_ghosts . x_ghosts.
class InterfaceMap {
 public:
  /// spacing = 0: one ghost per boundary node (a matching interface); > 0: along each edge at about that
  /// spacing (a non-matching interface; the ghosts at the edges' vertices are shared). Throws
  /// std::length_error before making any ghost if there would be more than 100 000.
  InterfaceMap(const InterfaceBoundary& boundary, double spacing);
  Index num_ghosts() const { return static_cast<Index>(ghosts_.size()); }
  /// Ghost positions in the reference configuration.
  const std::vector<Vec2>& reference() const { return reference_; }
  /// Pairs of ghosts that are neighbours along the boundary.
  const std::vector<std::pair<Index, Index>>& adjacent() const { return adjacent_; }
  Vec to_ghosts(const Vec& nodal) const;
  Vec to_nodes(const Vec& ghost) const;

 private:
  std::vector<std::vector<std::pair<Index, double>>> ghosts_;  // per ghost: (interface node, weight)
  std::vector<Vec2> reference_;
  std::vector<std::pair<Index, Index>> adjacent_;
  Index nodes_ = 0;
};

std::unique_ptr<PhysicsModel> make_dirichlet_neumann(Params p, const CaseContext& ctx, PhysicsModel& fluid,
                                                     PhysicsModel& structure);

}  // namespace lagfsi::fsi
