#pragma once
// Progress of a run on stderr (progress.cpp): on a terminal one status line redrawn in place, to a pipe or a
// file a line every few seconds of wall time and at each tenth of the run, and at the end a table of where
// the time went. The per-step numbers stay in log.csv.
#include <lagfsi/model.hpp>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi {

enum class ProgressMode { none, bar, lines };

/// "auto" (a bar when stderr is a terminal, lines otherwise), "bar", "lines" or "none"; --quiet is "none".
/// Returns false for another word.
bool parse_progress_mode(const std::string& word, bool quiet, ProgressMode& mode);

/// What the status shows after a step.
struct StepStatus {
  long step = 0;
  double t = 0, t_end = 1, dt = 0;
  int iterations = 0;  ///< Newton iterations of the step (inner ones for couplings)
  /// The models' metrics that have a progress label (Metric::progress_label): label and value, shown when
  /// the value is not 0 (e.g. fsi=3, a coupling's iterations).
  std::vector<std::pair<std::string, double>> shown;
  long particles = 0;  ///< particles of the models that move particles (0: none in the case)
  long nodes = 0;      ///< every body's nodes
  double wall = 0;     ///< seconds since the start of the run
};

/// Where the time of a run went, for the final table.
struct TimeTable {
  PhaseTimes phases;
  double wall = 0;  ///< the whole run (set-up, steps, output)
  long steps = 0;
  int retries = 0;  ///< steps retried with a smaller dt
  long iterations = 0;
  /// The labelled metrics summed over the run's steps, shown when not 0 (e.g. ", 412 fsi").
  std::vector<std::pair<std::string, double>> totals;
};

class Progress {
 public:
  /// `notes`: whether note() prints (not with --quiet); `lines_every`: seconds of wall time between two
  /// lines in lines mode.
  Progress(ProgressMode mode, std::string name, bool notes, std::FILE* out = stderr, double lines_every = 5.0);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// After each step.
  void step(const StepStatus& s);
  /// A message line of its own (a retried step), in every mode unless notes are off: the status line is
  /// cleared first and redrawn after.
  void note(const std::string& line);
  /// Ends the status line (the bar's last state stays on the screen).
  void finish();
  /// The final table (after finish()).
  void table(const TimeTable& t);

 private:
  void draw(const StepStatus& s);
  std::string status_text(const StepStatus& s, bool with_bar, int width) const;
  ProgressMode mode_;
  std::string name_;
  bool notes_;
  std::FILE* out_;
  double lines_every_;
  double last_line_wall_ = 0, last_draw_wall_ = -1;
  int last_tenth_ = 0;
  bool bar_shown_ = false;
  StepStatus last_{};
};

}  // namespace lagfsi
