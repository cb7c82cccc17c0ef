#pragma once
/// @file explicit_model.hpp
/// The lifecycle of an explicit model (the DEM, the MPM), shared: the driver's step is taken as sub-steps below the
/// model's stable step in one solve_iteration(), so that the model converges in one call (model.hpp).
///
///   predict(t_new, dt)     opens the step: the model saves its state at the step's start (save_step_start); a
///                          retry of a failed step (predict again before finalize_step) restores it instead
///                          (restore_step_start), so that the retried step starts from the same state as a clean
///                          one
///   solve_iteration()      advance(t_new, dt): the model's sub-steps up to t_new, timed into the assembly phase
///                          and its own wall time; reports convergence with the sub-steps as inner iterations
///   finalize_step()        closes the step
#include <lagfsi/model.hpp>

namespace lagfsi {

class ExplicitModel : public PhysicsModel {
 public:
  void predict(double t_new, double dt) final;
  IterationReport solve_iteration() final;
  void finalize_step() override { step_open_ = false; }

 protected:
  /// The state at the start of the step, kept for a retry, and put back by a retry.
  virtual void save_step_start() = 0;
  virtual void restore_step_start() = 0;
  /// The sub-steps from the model's time to t_new (dt the driver's step); returns how many were taken. Throws
  /// SolverError on an unstable or non-finite state.
  virtual int advance(double t_new, double dt) = 0;
  /// Wall time of the sub-steps so far (summary.json's particle-steps per second; kept by checkpoints).
  double wall_time_ = 0;

 private:
  bool step_open_ = false;  // predicted and not finalized
  double t_new_ = 0, dt_ = 0;
};

}  // namespace lagfsi
