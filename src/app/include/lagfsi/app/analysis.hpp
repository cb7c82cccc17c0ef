#pragma once
/// @file analysis.hpp
/// The driver: reads a case, builds its models through the registry, runs the time (or load) stepping
/// with Newton iterations per model, and writes resolved_case.json, the ParaView series, probes.csv,
/// log.csv and summary.json. Output files are flushed after every step, so a run that stops (error,
/// divergence, kill) leaves valid files behind; every write is checked (a full disk fails the run with exit
/// code 5, never "completed"). SIGINT and SIGTERM end the current step, write the output and set
/// summary.json's status to "interrupted". With "output": {"checkpoint": ...} the run writes checkpoints, from
/// which `--restart OUTDIR` continues it bit for bit (src/app/checkpoint.hpp).
#include <filesystem>
#include <string>
#include <vector>

namespace lagfsi {

struct RunOptions {
  std::filesystem::path case_file;
  std::filesystem::path out_dir;       ///< default: out/<case name>
  std::vector<std::string> overrides;  ///< "key.path=value"
  int threads = 0;                     ///< 0: OpenMP default
  bool quiet = false;
  std::string progress = "auto";  ///< auto | bar | lines | none (none when quiet)
  bool restart = false;           ///< continue from the last checkpoint in out_dir (--restart OUTDIR)
  long stop_after_step = 0;       ///< > 0: end after this step as if interrupted, status "stopped", exit 0
};

/// Exit codes of `lagfsi`. An interrupted run (SIGINT, SIGTERM) exits with 128 + the signal's number.
enum ExitCode : int {
  kOk = 0,
  kUsage = 1,
  kInputError = 2,
  kSolverError = 3,
  kInternalError = 4,
  kOutputError = 5,  ///< an output file could not be written (disk full, file-size limit, permissions)
};

/// Runs a case; returns an exit code. Errors are reported on stderr as one line; never throws.
int run_case(const RunOptions& opt);

/// Validates a case (building meshes and models) and prints the resolved case on stdout.
int check_case(const RunOptions& opt);

}  // namespace lagfsi
