#pragma once
// The observers of a run (run_observers.cpp): each writes one of the run's outputs as the simulation publishes its
// steps (simulation.hpp) — probes.csv, log.csv, the ParaView series, checkpoints, summary.json — or shows its
// progress. A restart resumes each from the checkpoint's position.
#include "checkpoint.hpp"
#include "progress.hpp"
#include "simulation.hpp"

#include <lagfsi/mpi_run.hpp>
#include <lagfsi/output_file.hpp>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace lagfsi {

/// probes.csv: a header, then a row at t = 0 and after every step (time, then every probe's columns).
class ProbesCsv final : public StepObserver {
 public:
  ProbesCsv(std::filesystem::path file, std::vector<Probe*> probes) : file_(std::move(file)), probes_(probes) {}
  void started(const Simulation& s) override;
  void resumed(const Simulation&, const RunPosition& pos) override { csv_.resume(file_, pos.probes_bytes); }
  void stepped(const Simulation& s, const StepRecord&) override { sample(s.time()); }
  std::uint64_t size() const { return csv_.size(); }

 private:
  void sample(double t);
  std::filesystem::path file_;
  std::vector<Probe*> probes_;
  AppendFile csv_;
};

/// log.csv: a row per step — step, time, dt, Newton iterations, residual, nodes, elements, the models' metrics
/// (model.hpp, Metric), then the wall time per phase (t_remesh .. t_output) and of the whole step (t_step); an MPI
/// run also the communication of process 0 since the last row (mpi_run::traffic): t_comm (wall seconds in the
/// collectives, waiting included), comm_MB (MB received in them), t_halo (wall seconds in the point-to-point waits of
/// PETSc's and hypre's halo exchanges) and petsc_MB (MB PETSc's messages sent).
class RunLog final : public StepObserver {
 public:
  explicit RunLog(std::filesystem::path file) : file_(std::move(file)) {}
  void started(const Simulation& s) override;
  void resumed(const Simulation&, const RunPosition& pos) override {
    csv_.resume(file_, pos.log_bytes);
    traffic_ = mpi_run::traffic();
  }
  void stepped(const Simulation& s, const StepRecord& r) override;
  std::uint64_t size() const { return csv_.size(); }

 private:
  std::filesystem::path file_;
  AppendFile csv_;
  mpi_run::Traffic traffic_;  // an MPI run: this process's communication up to the last row
};

/// The ParaView series of every body: the initial state, every `every`-th step and the last one, the state
/// where a run stopped early, and the last converged state of a run that failed (not after an output error).
class VtkSeries final : public StepObserver {
 public:
  /// `pieces_only`: the series of an MPI process other than 0, which writes only the models that write their own
  /// piece (PhysicsModel::writes_pieces).
  VtkSeries(bool enabled, int every, bool pieces_only = false)
      : enabled_(enabled), every_(every), pieces_only_(pieces_only) {}
  void started(const Simulation& s) override { write(s); }
  void resumed(const Simulation&, const RunPosition& pos) override { last_t_ = pos.last_output_t; }
  void output(const Simulation& s, const StepRecord& r) override {
    if (r.step % every_ == 0 || s.finished()) write(s);
  }
  void stopped_early(const Simulation& s) override { write(s); }
  void ended(const Simulation& s, RunEnd how) override;
  /// The time of the last state written (-1: none).
  double last_output_time() const { return last_t_; }
  /// Writes the bodies' state at the simulation's time (once per time).
  void write(const Simulation& s);

 private:
  bool enabled_;
  int every_;
  bool pieces_only_;
  double last_t_ = -1.0;
};

/// Checkpoints (checkpoint.hpp): every N steps and/or M minutes of wall time, and where a run stops early;
/// the position holds the sizes of the two CSV files and the series' last time.
class Checkpointer final : public StepObserver {
 public:
  struct Parts {
    std::filesystem::path dir, case_file;
    CheckpointSettings settings;
    RunPosition position;  ///< the case's hash and the thread count; the rest is filled in at each checkpoint
    std::vector<PhysicsModel*> models;  ///< bodies, then couplings
    std::vector<Probe*> probes;
    const ProbesCsv* probes_csv = nullptr;
    const RunLog* log = nullptr;
    const VtkSeries* series = nullptr;
    std::chrono::steady_clock::time_point start;  ///< when this run started
  };
  explicit Checkpointer(Parts parts);
  void resumed(const Simulation& s, const RunPosition&) override { last_step_ = s.step(); }
  void stepped(const Simulation& s, const StepRecord&) override;
  void stopped_early(const Simulation& s) override;
  /// The step of the last checkpoint written or read (-1: none).
  long last_step() const { return last_step_; }

 private:
  void save(const Simulation& s);
  Parts p_;
  double last_wall_ = 0;
  long last_step_ = -1;
};

/// The progress line and the retried steps' notes on stderr (progress.hpp); the final table is drawn by the
/// caller once the run's status is known.
class ProgressReport final : public StepObserver {
 public:
  ProgressReport(Progress& progress, std::string name, std::chrono::steady_clock::time_point start)
      : progress_(progress), name_(std::move(name)), start_(start) {}
  void stepped(const Simulation& s, const StepRecord& r) override;
  void retried(const Simulation&, const std::string& note) override { progress_.note("[" + name_ + "] " + note); }
  void ended(const Simulation&, RunEnd) override { progress_.finish(); }

 private:
  Progress& progress_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

/// summary.json: written at the start, every 50 steps and at the end (the caller's last write, with the status).
class SummaryWriter final : public StepObserver {
 public:
  struct Status {
    std::string value = "running", message;
  };
  struct Parts {
    std::filesystem::path file, case_file;
    std::string case_name;
    std::vector<std::string> warnings;
    int threads = 1;
    const Checkpointer* checkpointer = nullptr;
    long restarted_step = -1;                     ///< a restart: the checkpoint's step
    std::chrono::steady_clock::time_point start;  ///< when this run started
  };
  SummaryWriter(Parts parts, const Status& status) : p_(std::move(parts)), status_(status) {}
  /// An MPI run at its end: every process's phases, communication and memory (process_report), for the summary's
  /// "processes".
  Json processes;
  void started(const Simulation& s) override { write(s); }
  void resumed(const Simulation& s, const RunPosition&) override { write(s); }
  void stepped(const Simulation& s, const StepRecord& r) override {
    if (r.step % 50 == 0) write(s);
  }
  void write(const Simulation& s) const;

 private:
  Parts p_;
  const Status& status_;
};

/// An MPI run's processes side by side: each one's phase times (`phases`, summed over the run's steps, those before a
/// restart included), the wall time since it started (`wall`), its communication in this run (mpi_run::traffic:
/// seconds and MB received in the collectives, seconds in the halo exchanges' waits, MB PETSc's messages sent) and
/// its peak resident memory; an array in
/// rank order on process 0, null on the others and with one process. Every process must call it.
Json process_report(const PhaseTimes& phases, double wall);

/// JSON text for a file: never throws (every string is UTF-8 since the input is checked; any other byte would be
/// replaced).
std::string json_text(const Json& j);

}  // namespace lagfsi
