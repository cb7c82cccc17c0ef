#pragma once
// The time loop of a run (simulation.cpp): step control only — the step size, a failed step retried with half
// of it, the stop rules — publishing what happens to observers, which write the run's files and show its
// progress (run_observers.hpp). A model's numbers reach the observers as its step metrics (model.hpp), so a new
// model, metric or output touches its own file only. A distributed run would give its rank 0 the observers
// that write files, with the metrics reduced over the ranks before they are published.
#include "analysis_settings.hpp"
#include "checkpoint.hpp"

#include <lagfsi/model.hpp>

#include <functional>
#include <string>
#include <vector>

namespace lagfsi {

/// One accepted step, as the observers see it.
struct StepRecord {
  long step = 0;
  double t = 0, dt = 0;  ///< the time at the step's end and the step size it was taken with
  double dt_limit = 0;   ///< an adaptive step: the step it chose before any retry, and what set it
  std::string dt_by;
  int iterations = 0;   ///< Newton iterations of the step (inner ones of couplings, retried attempts too)
  double residual = 0;  ///< the last relative residual
  double wall = 0;      ///< seconds of wall time the step took (with its retried attempts)
  PhaseTimes phases;    ///< every body's phases of the step
  Index nodes = 0, elements = 0, particles = 0;
  std::vector<double> metrics;  ///< the models' metrics combined, in Simulation::metric_columns()'s order
};

class Simulation;

/// How a run ended: at its end time, stopped early (a signal, --stop-after-step), or with an error (an output
/// file that could not be written is told apart: nothing more is written then).
enum class RunEnd { completed, stopped, failed, output_failed };

/// Something that follows a run: each hook is called on every observer in the order they were added.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// A new run, after the models were initialized, before the first step (t = 0).
  virtual void started(const Simulation&) {}
  /// A run continued from a checkpoint, after the models' states were read back.
  virtual void resumed(const Simulation&, const RunPosition&) {}
  /// After a step: writes the step's output (the ParaView series). Called on every observer before stepped(),
  /// whose record then holds the time the models spent in it (phases.output).
  virtual void output(const Simulation&, const StepRecord&) {}
  virtual void stepped(const Simulation&, const StepRecord&) {}
  /// A step failed and is taken again with a smaller step; `note` says why, in one line.
  virtual void retried(const Simulation&, const std::string& note) { (void)note; }
  /// The loop stopped before the end time (a signal, a step limit), before ended().
  virtual void stopped_early(const Simulation&) {}
  /// The run is over (after the error, if any, was caught).
  virtual void ended(const Simulation&, RunEnd how) { (void)how; }
};

class Simulation {
 public:
  /// `bodies`: every body (their output, sizes, metrics); `couplings`: the couplings (their metrics);
  /// `steppers`: what a step advances, in order (the uncoupled bodies, then the couplings).
  Simulation(const AnalysisSettings& analysis, std::vector<PhysicsModel*> bodies, std::vector<PhysicsModel*> couplings,
             std::vector<PhysicsModel*> steppers);

  /// Observers are kept by reference and must outlive the run.
  void add(StepObserver& o) { observers_.push_back(&o); }

  /// Initializes the models and fixes the metric columns (log.csv) from their first report.
  void initialize();
  /// A new run: tells the observers (started).
  void start();
  /// A restart: the position and totals of the checkpoint (the models' states already read back).
  void resume(const RunPosition& pos, const RunTotals& totals);
  /// Steps until the end time, or until `stop()` is true between two steps. A step whose Newton iterations
  /// fail (SolverError: divergence, an element inverted, a singular matrix) is retried from the same state
  /// with half the step, up to max_step_halvings times; the next step goes back to the nominal dt. A remainder
  /// shorter than 1e-6 dt at the end is dropped. Errors propagate to the caller, who ends the run (end()).
  void run(const std::function<bool(const Simulation&)>& stop);
  /// Tells the observers how the run ended.
  void end(RunEnd how);

  bool finished() const { return analysis_.end_time - t_ <= 1e-6 * analysis_.dt; }
  long step() const { return step_; }
  double time() const { return t_; }
  long planned_steps() const;
  const AnalysisSettings& analysis() const { return analysis_; }
  const RunTotals& totals() const { return totals_; }
  const std::vector<PhysicsModel*>& bodies() const { return bodies_; }
  const std::vector<PhysicsModel*>& couplings() const { return couplings_; }
  /// The log's metric columns: each name once, in the order the models first reported them.
  const std::vector<Metric>& metric_columns() const { return columns_; }
  /// Labelled metrics (Metric::progress_label) of a step: label and value, for the progress line.
  std::vector<std::pair<std::string, double>> labelled(const StepRecord& r) const;
  /// The labelled metrics summed over the run's steps.
  std::vector<std::pair<std::string, double>> labelled_totals() const;

 private:
  /// One step from t_: its attempts (halving dt on a SolverError), then finalize_step; returns the record.
  StepRecord advance();
  /// The step to try from t_ (the analysis' dt, or the adaptive choice) and what set it.
  double choose_step(std::string& by) const;
  /// The bodies' phases, sizes and metrics of the step into its record.
  void record(StepRecord& r);
  /// The models' metrics combined by name in the columns' order.
  std::vector<double> combined_metrics() const;
  void account(const StepRecord& r);

  const AnalysisSettings& analysis_;
  std::vector<PhysicsModel*> bodies_, couplings_, steppers_;
  std::vector<StepObserver*> observers_;
  std::vector<Metric> columns_;
  RunTotals totals_;
  long step_ = 0;
  double t_ = 0;
};

}  // namespace lagfsi
