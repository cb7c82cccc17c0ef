#pragma once
/// @file analysis.hpp
/// The driver: reads a case, builds its models through the registry, runs the time (or load) stepping
/// with Newton iterations per model, and writes resolved_case.json, the ParaView series, probes.csv,
/// log.csv and summary.json. Output files are flushed after every step, so a run that stops (error,
/// divergence, kill) leaves valid files behind.
#include <filesystem>
#include <string>
#include <vector>

namespace lagfsi {

struct RunOptions {
  std::filesystem::path case_file;
  std::filesystem::path out_dir;          ///< default: out/<case name>
  std::vector<std::string> overrides;     ///< "key.path=value"
  int threads = 0;                        ///< 0: OpenMP default
  bool quiet = false;
};

/// Exit codes of `lagfsi`.
enum ExitCode : int { kOk = 0, kUsage = 1, kInputError = 2, kSolverError = 3, kInternalError = 4 };

/// Runs a case; returns an exit code. Errors are reported on stderr as one line; never throws.
int run_case(const RunOptions& opt);

/// Validates a case (building meshes and models) and prints the resolved case on stdout.
int check_case(const RunOptions& opt);

}  // namespace lagfsi
