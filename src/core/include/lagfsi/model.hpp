#pragma once
/// @file model.hpp
/// The lifecycle every physics model follows, so that one driver (and later the FSI loop) can advance
/// solids, fluids and MPM alike:
///
///   initialize()                once, before the first step (initial state, consistent accelerations)
///   predict(t_new, dt)          begin a step: store the old state, impose the prescribed values at t_new,
///                               set the first guess
///   solve_iteration()           one Newton correction: assemble, factorize, solve, update; returns the norms
///   finalize_step()             the step converged: update velocities/accelerations, commit the state
///   write_output(t)             ParaView output of the committed state
///   serialize(archive)          checkpoints: writes the state after finalize_step, or (restart) reads it back
///                               after initialize(), so that the next step is the one the run would have taken
///
/// Probes are created by the model that owns the quantity (make_probe) and sampled after finalize_step.
#include <lagfsi/params.hpp>
#include <lagfsi/state_archive.hpp>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

/// Wall-clock seconds spent per phase (accumulated by the model, reset by the driver each step).
struct PhaseTimes {
  double remesh = 0, assembly = 0, factorization = 0, solve = 0, output = 0;
  PhaseTimes& operator+=(const PhaseTimes& o) {
    remesh += o.remesh;
    assembly += o.assembly;
    factorization += o.factorization;
    solve += o.solve;
    output += o.output;
    return *this;
  }
};

/// Norms of one Newton iteration: the residual at the iterate the call started from, and the correction
/// it applied. Convergence (decided by the model, reported in `converged`): residual <= rtol *
/// residual_ref at an iterate whose last correction was <= xtol * increment_ref (the body's size); a
/// converged call applies no correction, so the last factorization of a step is not wasted.
struct IterationReport {
  double residual = 0, residual_ref = 0, increment = 0, increment_ref = 1;
  bool converged = false;
  int inner_iterations = 0;  ///< a composite model (a coupling): the sub-solver iterations this call ran
};

/// A number a model reports after each step (PhysicsModel::step_metrics): a column of log.csv.
struct Metric {
  enum class Combine { sum, max };
  std::string name;  ///< the column's name (an identifier)
  double value = 0;
  Combine combine = Combine::sum;  ///< two models with the same name: their sum or their maximum
  /// Shown in the progress line as " label=value" when not empty and the value is not 0; its sum over the
  /// run's steps goes to the final table as ", total label".
  std::string progress_label = {};
};

/// The keys of a probe's KeyTable: those of every probe (name, type, body) then the type's own. With one type
/// "type" defaults to it; with several (one table for types that take the same keys) it is listed as required.
std::vector<KeyDecl> probe_keys(const std::vector<std::string>& types, std::vector<KeyDecl> own);

/// One or more columns of probes.csv.
class Probe {
 public:
  virtual ~Probe() = default;
  virtual std::vector<std::string> columns() const = 0;
  virtual std::vector<double> sample() const = 0;
  /// A probe that keeps something from step to step (a peak, a chosen particle) saves it here (checkpoints).
  virtual void serialize(StateArchive&) {}
};

/// The largest step a model can take from its present state, and what sets it (PhysicsModel::stable_step).
struct StepLimit {
  double dt = std::numeric_limits<double>::infinity();
  std::string by;  ///< e.g. "courant", "acceleration"; empty: no limit
};

class PhysicsModel {
 public:
  virtual ~PhysicsModel() = default;
  virtual std::string name() const = 0;
  virtual std::string type() const = 0;
  virtual void initialize() = 0;
  virtual void predict(double t_new, double dt) = 0;
  virtual IterationReport solve_iteration() = 0;
  virtual void finalize_step() = 0;
  virtual void write_output(double t) = 0;
  /// True for a model that writes its own part of the output on every process of an MPI run (parallel VTK: one
  /// piece per process, process 0 the .pvtu that lists them): its write_output is called on every process, the
  /// others' on process 0 only.
  virtual bool writes_pieces() const { return false; }
  /// Creates a probe of this model from its case-file parameters (the "type" selects it).
  virtual std::unique_ptr<Probe> make_probe(Params p) = 0;

  virtual Index num_nodes() const = 0;
  virtual Index num_elements() const = 0;
  /// Particles the model moves (PFEM, MPM, DEM); 0 for a mesh-only model. The progress line shows them.
  virtual Index num_particles() const { return 0; }
  /// The model's own numbers after an accepted step (after finalize_step): each one a column of log.csv,
  /// the same name from two models combined as Metric::combine says. A model reports the same names at
  /// every step (the columns are fixed by the first call, made after initialize()).
  virtual std::vector<Metric> step_metrics() const { return {}; }
  /// The model's own numbers for summary.json (an object merged into its entry; empty: none).
  virtual Json summary() const { return Json::object(); }
  /// What the body's input chose on purpose against the safe default, or got unlike it asked, each line
  /// starting with its JSON path: printed as warnings and listed in summary.json's "warnings" (empty: none).
  virtual std::vector<std::string> warnings() const { return {}; }
  /// An adaptive step's limit from the model's present state (after initialize or finalize_step) for the Courant
  /// number `courant` (/analysis/time_step). None by default (implicit models; explicit ones sub-step).
  virtual StepLimit stable_step(double courant) const {
    (void)courant;
    return {};
  }
  PhaseTimes& times() { return times_; }
  const PhaseTimes& times() const { return times_; }

  /// Checkpoints (`output.checkpoint`, `lagfsi run --restart`): whether serialize() is implemented.
  virtual bool can_checkpoint() const { return false; }
  /// Everything the time loop needs to continue bit for bit from the end of a step (after finalize_step):
  /// the state, the integrator's and accumulators' history, counters, the output series (state_archive.hpp).
  /// A restart builds the case, calls initialize() and then this with a reading archive, which overwrites
  /// what initialize() set. The default throws std::logic_error (can_checkpoint() is false).
  virtual void serialize(StateArchive& ar);

 protected:
  PhaseTimes times_;
};

/// Runs m.solve_iteration() until the model reports convergence (after m.predict()). Returns the
/// iterations done (inner ones for composite models). Throws SolverError naming the body when the relative
/// residual is not finite or above 1e12, or when max_iterations pass without convergence; `relative`
/// receives the last relative residual.
int iterate_to_convergence(PhysicsModel& m, int max_iterations, double t_new, double* relative = nullptr);

}  // namespace lagfsi
