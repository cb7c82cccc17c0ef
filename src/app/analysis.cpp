#include "case_builder.hpp"
#include "checkpoint.hpp"
#include "input_checks.hpp"
#include "interrupt.hpp"
#include "output_lock.hpp"
#include "progress.hpp"
#include "run_observers.hpp"
#include "simulation.hpp"

#include <lagfsi/app/analysis.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/mpi_run.hpp>
#include <lagfsi/output_file.hpp>
#include <lagfsi/stopwatch.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <new>

#ifdef LAGFSI_HAVE_OPENMP
#include <omp.h>
#endif

namespace lagfsi {

namespace fs = std::filesystem;

int check_case(const RunOptions& opt) {
  const auto c = build_case_or_report(opt, true);
  if (!c) return kInputError;
  for (const auto& w : c->warnings) std::cerr << "lagfsi: warning: " << w << "\n";
  std::cout << json_text(c->root.json()) << std::flush;
  if (!std::cout) {
    std::cerr << "lagfsi: error: stdout: cannot write (" << errno_reason(errno) << ")\n";
    return kOutputError;
  }
  return kOk;
}

namespace {

/// The output folder of a run: not the case file's own, not in use by another run (locked until the run ends),
/// created; a restart's must hold an earlier run. Returns false after printing the one-line error.
bool prepare_output_folder(const RunOptions& opt, const fs::path& out, OutputLock& lock) {
  try {
    check_output_folder(opt.case_file, out);
  } catch (const InputError& e) {
    std::cerr << "lagfsi: error: " << e.what() << "\n";
    return false;
  }
  if (opt.restart && !fs::is_directory(out)) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": --restart: " << out.string()
              << " is not a folder of an earlier run\n";
    return false;
  }
  try {
    fs::create_directories(out);
    if (!fs::is_directory(out)) throw std::runtime_error("it is not a folder");
  } catch (const std::exception& e) {
    const auto* fe = dynamic_cast<const fs::filesystem_error*>(&e);
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": cannot write the output folder " << out.string()
              << " (" << (fe ? fe->code().message() : std::string(e.what())) << ")\n";
    return false;
  }
  if (const std::string why = lock.acquire(out); !why.empty()) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": the output folder " << out.string() << " is "
              << (why.rfind("in use", 0) == 0 ? why : "not usable: " + why) << "\n";
    return false;
  }
  return true;
}

/// A restart: the checkpoint in `out` must be of this case and the CSV files at least as long as it says;
/// otherwise one line, and the earlier run's files stay as they are. Returns false after printing it.
bool open_restart_or_report(const RunOptions& opt, const fs::path& out, int threads, RunPosition& pos, RunTotals& tot,
                            std::unique_ptr<StateArchive>& restart) {
  if (!opt.restart) return true;
  try {
    restart = std::make_unique<StateArchive>(open_restart(out, pos, tot, opt.case_file));
  } catch (const InputError& e) {
    std::cerr << "lagfsi: error: " << e.what() << "\n";
    return false;
  }
  if (pos.threads != threads && !opt.quiet)
    std::cerr << "lagfsi: warning: the checkpoint was written with " << pos.threads << " threads, this run has "
              << threads << ": the results may differ from an uninterrupted run in the last digits\n";
  return true;
}

std::vector<PhysicsModel*> pointers(const std::vector<std::unique_ptr<PhysicsModel>>& v) {
  std::vector<PhysicsModel*> p;
  for (const auto& m : v) p.push_back(m.get());
  return p;
}

/// The observers of a run, in the order the simulation calls them: the CSV files before the checkpoint that
/// records their sizes, the checkpoint before the series (a run stopped early writes its last state after its
/// checkpoint, so that a restart continues the series as if it had not stopped).
struct RunOutputs {
  RunOutputs(const Case& c, const RunOptions& opt, Progress& progress, const SummaryWriter::Status& status, int threads,
             SteadyClock::time_point start, long restarted_step)
      : probes(c.ctx.out_dir / "probes.csv", probe_list(c)),
        log(c.ctx.out_dir / "log.csv"),
        checkpointer({c.ctx.out_dir, opt.case_file, c.checkpoint,
                      RunPosition{case_hash(c.root.json()), 0, 0, -1, 0, 0, threads}, all_models(c), probe_list(c),
                      &probes, &log, &series, start}),
        series(c.vtk, c.output_every),
        pieces(c.vtk, c.output_every, true),
        report(progress, c.name, start),
        summary({c.ctx.out_dir / "summary.json", opt.case_file, c.name, c.warnings, threads, &checkpointer,
                 restarted_step, start},
                status) {}
  static std::vector<Probe*> probe_list(const Case& c) {
    std::vector<Probe*> v;
    for (const auto& p : c.probes) v.push_back(p.get());
    return v;
  }
  void attach(Simulation& sim) {
    for (StepObserver* o :
         std::initializer_list<StepObserver*>{&probes, &log, &checkpointer, &series, &report, &summary})
      sim.add(*o);
  }
  ProbesCsv probes;
  RunLog log;
  Checkpointer checkpointer;
  VtkSeries series;
  VtkSeries pieces;  // the other MPI processes' series: the models that write a piece each
  ProgressReport report;
  SummaryWriter summary;
};

/// Starts the run, or continues it from the checkpoint in its folder (the CSV files cut back to its step).
void start_or_resume(Simulation& sim, Case& c, const RunOptions& opt, std::unique_ptr<StateArchive>& restart,
                     const RunPosition& pos, const RunTotals& tot) {
  sim.initialize();
  if (restart) {
    try {
      serialize_run_models(*restart, all_models(c), RunOutputs::probe_list(c));
    } catch (const CheckpointError& e) {
      throw InputError(opt.case_file.string(), "",
                       std::string("--restart: the checkpoint does not fit the case (") + e.what() + ")");
    }
    restart.reset();
    sim.resume(pos, tot);
    return;
  }
  // A new run: the checkpoints of an earlier one in the folder are not its own (an MPI run: process 0 writes).
  if (mpi_run::writer()) {
    for (const char* f : {kCheckpointFile, kCheckpointPrevFile}) fs::remove(c.ctx.out_dir / f);
    write_file_atomic(c.ctx.out_dir / "resolved_case.json", json_text(c.root.json()));
  }
  sim.start();
}

/// Runs the loop; an error becomes the run's status, message and exit code. The message of an input error in the
/// case file (one the run finds, e.g. an inflow into water with no way out) leaves out the file, which the error's
/// line names already.
int run_loop(Simulation& sim, const std::function<void()>& body, SummaryWriter::Status& status,
             const std::string& case_file) {
  try {
    body();
    return kOk;
  } catch (const OutputError& e) {
    status.message = e.what();
    sim.end(RunEnd::output_failed);
    return kOutputError;
  } catch (const SolverError& e) {
    status.message = e.what();
    sim.end(RunEnd::failed);
    return kSolverError;
  } catch (const InputError& e) {
    status.message =
        e.file() == case_file ? (e.json_path().empty() ? "/" : e.json_path()) + ": " + e.reason() : e.what();
    sim.end(RunEnd::failed);
    return kInputError;
  } catch (const std::bad_alloc&) {
    status.message = "out of memory at t = " + std::to_string(sim.time());
    sim.end(RunEnd::failed);
    return kSolverError;
  } catch (const std::exception& e) {
    status.message = e.what();
    sim.end(RunEnd::failed);
    return kInternalError;
  }
}

/// The run's status after its loop (completed, stopped, interrupted, failed) and the exit code it gives.
int settle_status(const Simulation& sim, int code, SummaryWriter::Status& status) {
  const int sig = InterruptGuard::received();
  const std::string where = " after step " + std::to_string(sim.step()) + " at t = " + std::to_string(sim.time());
  if (code != kOk)
    status.value = "failed";
  else if (sim.finished())
    status.value = "completed";
  else if (sig != 0) {
    status.value = "interrupted";
    status.message = std::string("interrupted by ") + signal_name(sig) + where;
    return 128 + sig;
  } else {
    status.value = "stopped";
    status.message = "stopped" + where + " (--stop-after-step)";
  }
  return code;
}

/// The last lines on stderr: the table of where the time went and what became of the run.
void report_end(const Simulation& sim, const Case& c, const RunOptions& opt, Progress& progress, int code,
                const SummaryWriter::Status& status, long checkpoint_step, double wall) {
  if (code == kOk || code > 128) {
    TimeTable table;
    table.phases = sim.totals().phases;
    table.wall = sim.totals().wall_before + wall;
    table.steps = sim.totals().steps;
    table.retries = sim.totals().retries;
    table.iterations = sim.totals().iterations;
    table.totals = sim.labelled_totals();
    progress.table(table);
  }
  const fs::path& out = c.ctx.out_dir;
  const std::string resume =
      checkpoint_step >= 0 && !sim.finished() ? "; continue it with --restart " + out.string() : "";
  if (code > 128 || (code == kOk && !sim.finished())) {
    if (!opt.quiet || code > 128)
      std::cerr << "lagfsi: " << status.message << "; output written to " << out.string() << resume << "\n";
  } else if (code == kOk && !opt.quiet) {
    std::fprintf(stderr, "[%s] done: %d steps, %ld Newton iterations, %.2f s -> %s\n", c.name.c_str(),
                 sim.totals().steps, sim.totals().iterations, wall, out.string().c_str());
  }
}

}  // namespace

int run_case(const RunOptions& opt) {
  const auto t_start = SteadyClock::now();
#ifdef LAGFSI_HAVE_OPENMP
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const int threads = omp_get_max_threads();
#else
  const int threads = 1;
#endif
  // From here on Ctrl-C ends the run at the next step (a second one stops at once); while the case is built
  // (meshes), as soon as it is.
  const InterruptGuard interrupt_guard;
  const std::unique_ptr<Case> cp = build_case_or_report(opt, false);
  if (!cp) return kInputError;
  if (const int sig = InterruptGuard::received()) {
    std::cerr << "lagfsi: interrupted by " << signal_name(sig) << " while the case was being built; nothing written\n";
    return 128 + sig;
  }
  Case& c = *cp;
  // An MPI run (mpi_run.hpp): every process runs the case, process 0 alone writes the folder (the others print
  // nothing: app_main silenced them).
  const bool writer = mpi_run::writer();
  OutputLock lock;
  if (mpi_run::any(writer && !prepare_output_folder(opt, c.ctx.out_dir, lock))) return kInputError;
  RunPosition pos{case_hash(c.root.json())};
  RunTotals tot;
  std::unique_ptr<StateArchive> restart;
  if (!open_restart_or_report(opt, c.ctx.out_dir, threads, pos, tot, restart)) return kInputError;
  for (const auto& w : c.warnings)
    if (!opt.quiet) std::cerr << "lagfsi: warning: " << w << "\n";

  ProgressMode mode = ProgressMode::none;
  parse_progress_mode(opt.progress, opt.quiet, mode);
  Progress progress(mode, c.name, !opt.quiet);
  SummaryWriter::Status status;
  Simulation sim(c.ctx.analysis, pointers(c.models), pointers(c.couplings), c.steppers);
  RunOutputs outputs(c, opt, progress, status, threads, t_start, restart ? pos.step : -1);
  if (writer)
    outputs.attach(sim);
  else
    sim.add(outputs.pieces);
  int code = run_loop(
      sim,
      [&] {
        start_or_resume(sim, c, opt, restart, pos, tot);
        sim.run([&](const Simulation& s) {  // every process stops at the same step
          return mpi_run::any(InterruptGuard::received() ||
                              (opt.stop_after_step > 0 && s.step() >= opt.stop_after_step));
        });
        sim.end(sim.finished() ? RunEnd::completed : RunEnd::stopped);
      },
      status, opt.case_file.string());
  if (code != kOk) std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << status.message << "\n";
  // Process 0's output failed (the only failure the processes do not all see): the others are stopped with it.
  if (code == kOutputError) mpi_run::abort_all(code);
  outputs.summary.processes = process_report(sim.totals().phases, seconds_since(t_start));
  code = settle_status(sim, code, status);
  try {
    if (writer) outputs.summary.write(sim);
  } catch (const std::exception& e) {
    // After a failure its message has been printed: one line per run.
    if (code == kOk || code > 128) {
      std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << e.what() << "\n";
      code = dynamic_cast<const OutputError*>(&e) ? kOutputError : kInternalError;
    }
  }
  report_end(sim, c, opt, progress, code, status, outputs.checkpointer.last_step(), seconds_since(t_start));
  return code;
}

}  // namespace lagfsi
