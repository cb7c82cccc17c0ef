#pragma once
// Checkpoints of a run and `lagfsi run CASE --restart OUTDIR` (checkpoint.cpp). The case's
// "output": {"checkpoint": {"every_steps": N, "every_minutes": M, "keep": 2}} writes OUTDIR/checkpoint.bin
// every N steps and/or every M minutes of wall time, and when a signal (or --stop-after-step) ends the run
// early. A checkpoint holds where the run is (step, time, the sizes of probes.csv and log.csv at that step,
// the totals of summary.json) and every body's, coupling's and probe's serialize() (model.hpp), so that a
// restart continues bit for bit like the run that was not stopped (with the same number of threads).
#include <lagfsi/model.hpp>
#include <lagfsi/params.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lagfsi {

struct CheckpointSettings {
  long every_steps = 0;      ///< 0: not by steps
  double every_minutes = 0;  ///< 0: not by wall time
  int keep = 2;              ///< 1: the last checkpoint only; 2: also the one before (checkpoint.prev.bin)
  bool active() const { return every_steps > 0 || every_minutes > 0; }
};

/// Validates /output/checkpoint (an object; defaults filled in) and reads it.
CheckpointSettings read_checkpoint_settings(Params checkpoint);

/// The case's fingerprint for --restart: FNV-1a (64 bits) of the resolved case (defaults and --set applied)
/// without /output/checkpoint, which may change between the runs.
std::uint64_t case_hash(const Json& resolved_case);

/// summary.json's running totals (carried over by a restart).
struct RunTotals {
  PhaseTimes phases;
  std::vector<PhaseTimes> body_phases;  // per model, in the case's order
  long iterations = 0;
  int retries = 0;
  int max_iterations = 0;
  int steps = 0;
  /// The models' labelled metrics (Metric::progress_label) summed over the steps, in the log's column order.
  std::vector<double> labelled;
  double wall_before = 0;  // wall time of the runs before a restart
  /// An adaptive step: the last accepted step, and how many steps each limit set (names and counts).
  double last_dt = 0;
  std::vector<std::string> dt_by;
  std::vector<long> dt_by_steps;
  double dt_min = 0, dt_max = 0;
};

/// Where the run is at a checkpoint.
struct RunPosition {
  std::uint64_t case_hash = 0;
  long step = 0;
  double t = 0, last_output_t = -1;
  std::uint64_t probes_bytes = 0, log_bytes = 0;  // probes.csv and log.csv after the step's rows
  int threads = 0;
};

/// The checkpoint's contents, writing or reading (ar.loading()): first the position and totals (reading
/// checks pos.case_hash, set beforehand, against the checkpoint's: InputError naming the case file when they
/// differ), then every model (bodies, then couplings) and probe (CheckpointError when they are not those of
/// the checkpoint).
void serialize_run_head(StateArchive& ar, RunPosition& pos, RunTotals& tot, const std::filesystem::path& case_file);
void serialize_run_models(StateArchive& ar, const std::vector<PhysicsModel*>& models,
                          const std::vector<Probe*>& probes);

/// Bodies and couplings that cannot be checkpointed (EFG) with checkpoints asked for: InputError at
/// /output/checkpoint, or naming the case file for --restart (`restart`).
void check_checkpointable(const std::vector<PhysicsModel*>& models, const Params& output, bool restart,
                          const std::filesystem::path& case_file);

/// Writes a checkpoint of the run at `pos` (its step, time and CSV sizes filled in by the caller) into `dir`.
void save_checkpoint(const std::filesystem::path& dir, int keep, RunPosition& pos, const RunTotals& tot,
                     const std::vector<PhysicsModel*>& models, const std::vector<Probe*>& probes,
                     const std::filesystem::path& case_file);

/// --restart: the newest checkpoint in `dir`, its position and totals read (pos.case_hash, set beforehand,
/// checked against it) and probes.csv and log.csv checked to be at least as long as it says. Returns the
/// archive, positioned at the models (serialize_run_models). InputError naming the case file otherwise.
StateArchive open_restart(const std::filesystem::path& dir, RunPosition& pos, RunTotals& tot,
                          const std::filesystem::path& case_file);

/// Writes OUTDIR/checkpoint.bin atomically (a temporary file, fsync, rename, fsync of the folder); with keep
/// = 2 the previous one is kept as checkpoint.prev.bin. Throws OutputError.
void write_checkpoint(const std::filesystem::path& dir, const std::string& payload, int keep);

/// The payload of the newest intact checkpoint in `dir` (checkpoint.bin, else checkpoint.prev.bin: a run
/// killed while replacing one); InputError (file = case_file) when there is none.
std::string read_checkpoint(const std::filesystem::path& dir, const std::filesystem::path& case_file);

inline constexpr const char* kCheckpointFile = "checkpoint.bin";
inline constexpr const char* kCheckpointPrevFile = "checkpoint.prev.bin";

}  // namespace lagfsi
