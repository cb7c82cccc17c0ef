#pragma once
/// @file coupling.hpp
/// The Dirichlet–Neumann fixed-point loop of a strongly coupled partitioned time step (docs/theory/fsi.md; the coupling
/// verbs follow preCICE: write data, advance, read data, check convergence, accelerate).
///
/// Within one time step, from an interface guess x_0 (e.g. the solid's predicted interface positions):
///   f_k   = D(x_k)     the Dirichlet side (fluid) advanced with the interface at x_k; returns the interface
///                      forces it exerts on the other side (equal and opposite to those it feels)
///   x~_k  = N(f_k)     the Neumann side (solid) advanced under those forces; returns its interface positions
///   r_k   = x~_k - x_k converged when |r_k| <= tolerance * reference (reference: the step's interface
///                      motion, supplied by the caller, or |x~_k - x_0| when it passes 0)
///   x_{k+1} = acceleration(x_k, x~_k)
/// Each side is re-run from the start-of-step state at every iteration (the sides own that reset). A loop that
/// does not converge in max_iterations returns converged = false (the caller decides: retry with a smaller
/// step, or fail with a message); it never throws for that.
#include <lagfsi/fsi/acceleration.hpp>
#include <lagfsi/types.hpp>

#include <functional>

namespace lagfsi::fsi {

struct CouplingSettings {
  int max_iterations = 50;
  double tolerance = 1e-6;  ///< relative to the reference interface motion
  /// Interface positions at the start of the step: with reference = 0 the residual is compared with the
  /// step's motion |x~ - origin| (empty: the initial guess x_0 stands for it), never below reference_floor.
  Vec origin;
  double reference_floor = 1e-300;
};

struct CouplingReport {
  int iterations = 0;    ///< coupling passes (fluid + solid solves) done
  double residual = 0;   ///< |r| of the last pass
  double reference = 0;  ///< the motion the residual was compared with
  bool converged = false;
};

/// The two sides as callables: dirichlet(x) -> interface forces, neumann(f) -> interface positions.
using DirichletSide = std::function<Vec(const Vec& interface_positions)>;
using NeumannSide = std::function<Vec(const Vec& interface_forces)>;

/// Runs the loop of one time step. `x` holds the initial guess on entry and the last accepted interface
/// positions on exit (x~ of the converged pass). `reference` > 0 fixes the residual scale; 0 takes the motion
/// of the interface within the step, |x~ - origin| (settings), with the settings' floor.
CouplingReport dirichlet_neumann_step(const DirichletSide& dirichlet, const NeumannSide& neumann,
                                      Acceleration& acceleration, Vec& x, const CouplingSettings& settings,
                                      double reference = 0.0);

}  // namespace lagfsi::fsi
