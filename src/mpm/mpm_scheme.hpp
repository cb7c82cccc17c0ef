#pragma once
// The time schemes of an MPM body, chosen once when the body is read (mpm_input.cpp):
//  - explicit single phase, "update" "musl" | "usl" | "usf" (mpm_scheme_explicit.cpp);
//  - explicit saturated two-phase, the v-w formulation (mpm_two_phase.cpp);
//  - implicit (Newmark or generalized-alpha on the grid, mpm_implicit.cpp).
// The explicit ones split the driver's step into sub-steps dt_sub <= cfl h / c, c the P-wave speed
// (mpm_scheme.cpp): the step-size control of the explicit member of the time-integrator contract, which the
// single-phase scheme steps its grid with. The two-phase scheme keeps its own update of the two grid velocity
// fields (the drag couples them implicitly per node, outside the contract's diagonal-mass form).
#include "mpm_body.hpp"

#include <lagfsi/linear_solver.hpp>
#include <lagfsi/time_integrator.hpp>

#include <memory>

namespace lagfsi::mpm {

class MpmScheme {
 public:
  virtual ~MpmScheme() = default;
  /// Advances the body from b.t over the driver's step dt to t_new (b.t = t_new at the end); returns the
  /// number of sub-steps taken.
  virtual int advance(MpmBody& b, double t_new, double dt) = 0;
};

/// An explicit scheme: sub-steps dt_sub = dt / n <= cfl h / c, c = wave_speed(), the grid reset every sub-step.
class ExplicitScheme : public MpmScheme {
 public:
  int advance(MpmBody& b, double t_new, double dt) final;
  /// The P-wave speed of the stable step (with water, it includes K_w / n).
  virtual double wave_speed(const MpmBody& b) const = 0;

 protected:
  /// One sub-step from b.t to b.t + dt.
  virtual void substep(MpmBody& b, double dt) = 0;
};

/// The particle stress update rule of the explicit single-phase scheme ("update").
enum class StressUpdate { Musl, Usl, Usf };

/// integrator: the central difference (make_time_integrator), which takes every sub-step's grid update.
std::unique_ptr<ExplicitScheme> make_explicit_scheme(StressUpdate update, std::unique_ptr<TimeIntegrator> integrator);
std::unique_ptr<ExplicitScheme> make_two_phase_scheme();
std::unique_ptr<MpmScheme> make_implicit_scheme(std::unique_ptr<TimeIntegrator> integrator,
                                                std::unique_ptr<LinearSolver> solver);

/// Linear elastic small-strain update of particle q from the gradient G of its displacement increment: stress,
/// strain, deformation gradient and volume (the two-phase and implicit schemes).
void elastic_increment(Particles& P, Index q, const Mat2& G, const MpmMaterial& mat);

}  // namespace lagfsi::mpm
