// Progress of a run (progress.hpp). A bar is redrawn at most ten times a second (and at the last step); a
// line is printed when `lines_every` seconds of wall time have passed since the last one or the run has
// crossed a tenth of its time. Nothing here touches log.csv, which keeps one row per step.
#include "progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>

namespace lagfsi {

namespace {

/// "12.3s", "4m05s", "2h03m".
std::string duration(double s) {
  char buf[32];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", s);
  } else if (s < 3600) {
    const long m = static_cast<long>(s / 60);
    std::snprintf(buf, sizeof buf, "%ldm%02lds", m, static_cast<long>(s - 60.0 * m));
  } else {
    const long h = static_cast<long>(s / 3600);
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", h, static_cast<long>((s - 3600.0 * h) / 60));
  }
  return buf;
}

int terminal_width(std::FILE* out) {
  winsize ws{};
  if (::ioctl(::fileno(out), TIOCGWINSZ, &ws) == 0 && ws.ws_col >= 20) return ws.ws_col;
  return 100;
}

double fraction(const StepStatus& s) { return s.t_end > 0 ? std::clamp(s.t / s.t_end, 0.0, 1.0) : 1.0; }

}  // namespace

bool parse_progress_mode(const std::string& word, bool quiet, ProgressMode& mode) {
  if (word == "auto")
    mode = ::isatty(STDERR_FILENO) ? ProgressMode::bar : ProgressMode::lines;
  else if (word == "bar")
    mode = ProgressMode::bar;
  else if (word == "lines")
    mode = ProgressMode::lines;
  else if (word == "none")
    mode = ProgressMode::none;
  else
    return false;
  if (quiet) mode = ProgressMode::none;
  return true;
}

Progress::Progress(ProgressMode mode, std::string name, bool notes, std::FILE* out, double lines_every)
    : mode_(mode), name_(std::move(name)), notes_(notes), out_(out), lines_every_(lines_every) {}

Progress::~Progress() { finish(); }

std::string Progress::status_text(const StepStatus& s, bool with_bar, int width) const {
  const double f = fraction(s);
  const double eta = s.t > 0 ? s.wall / s.t * (s.t_end - s.t) : NAN;
  // The numbers first (snprintf, not " fsi=" + std::to_string(...): a false -Wrestrict of GCC 12, bug 105329).
  char buf[256];
  std::snprintf(buf, sizeof buf, "%3.0f%% step %ld t=%.4g/%.4g dt=%.3g it=%d", 100 * f, s.step, s.t, s.t_end, s.dt,
                s.iterations);
  std::string nums = buf;
  for (const auto& [label, value] : s.shown)
    if (value != 0) {
      std::snprintf(buf, sizeof buf, " %s=%.6g", label.c_str(), value);
      nums += buf;
    }
  std::snprintf(buf, sizeof buf, s.particles > 0 ? " particles=%ld" : " nodes=%ld",
                s.particles > 0 ? s.particles : s.nodes);
  nums += buf;
  std::snprintf(buf, sizeof buf, " wall=%s eta=%s", duration(s.wall).c_str(), duration(eta).c_str());
  nums += buf;
  std::string text;
  if (!with_bar) {
    text = "[" + name_ + "] ";
    text += nums;
    return text;
  }
  // On a terminal: the numbers always, then the bar and the case name as far as the width allows (a line
  // longer than the terminal wraps, and "\r" then redraws only its last part).
  const int room = width - 1 - static_cast<int>(nums.size());
  const int name_len = static_cast<int>(name_.size()) + 3;
  const int cells = std::clamp(room - 3 - (room - 3 - 10 >= name_len ? name_len : 0), 0, 20);
  if (room - 3 - cells >= name_len) text = "[" + name_ + "] ";
  if (cells >= 5) {
    const int full = static_cast<int>(std::floor(f * cells));
    text += '[';
    text.append(static_cast<size_t>(full), '#');
    text.append(static_cast<size_t>(cells - full), '-');
    text += "] ";
  }
  text += nums;
  if (width > 0 && static_cast<int>(text.size()) > width - 1) text.resize(static_cast<size_t>(width - 1));
  return text;
}

void Progress::draw(const StepStatus& s) {
  std::fprintf(out_, "\r%s\033[K", status_text(s, true, terminal_width(out_)).c_str());
  std::fflush(out_);
  bar_shown_ = true;
  last_draw_wall_ = s.wall;
}

void Progress::step(const StepStatus& s) {
  last_ = s;
  const bool last_step = s.t >= s.t_end * (1 - 1e-12);
  if (mode_ == ProgressMode::bar) {
    if (last_step || last_draw_wall_ < 0 || s.wall - last_draw_wall_ >= 0.1) draw(s);
  } else if (mode_ == ProgressMode::lines) {
    const int tenth = static_cast<int>(std::floor(10 * fraction(s) + 1e-9));
    if (tenth > last_tenth_ || s.wall - last_line_wall_ >= lines_every_) {
      std::fprintf(out_, "%s\n", status_text(s, false, 0).c_str());
      std::fflush(out_);
      last_tenth_ = std::max(last_tenth_, tenth);
      last_line_wall_ = s.wall;
    }
  }
}

void Progress::note(const std::string& line) {
  if (!notes_) return;
  if (bar_shown_) std::fprintf(out_, "\r\033[K");
  std::fprintf(out_, "%s\n", line.c_str());
  if (bar_shown_) draw(last_);
  std::fflush(out_);
}

void Progress::finish() {
  if (bar_shown_) std::fprintf(out_, "\n");
  bar_shown_ = false;
  std::fflush(out_);
}

void Progress::table(const TimeTable& t) {
  if (mode_ == ProgressMode::none) return;
  const PhaseTimes& p = t.phases;
  const double counted = p.remesh + p.assembly + p.factorization + p.solve + p.output;
  std::fprintf(out_,
               "[%s] where the time went: %s wall, %ld steps (%d retried with a smaller dt), %ld Newton iterations",
               name_.c_str(), duration(t.wall).c_str(), t.steps, t.retries, t.iterations);
  for (const auto& [label, total] : t.totals)
    if (total != 0) std::fprintf(out_, ", %.6g %s", total, label.c_str());
  std::fprintf(out_, "\n");
  const std::pair<const char*, double> rows[] = {
      {"remesh", p.remesh}, {"assembly", p.assembly}, {"factorization", p.factorization},
      {"solve", p.solve},   {"output", p.output},     {"other", std::max(0.0, t.wall - counted)}};
  for (const auto& [phase, seconds] : rows)
    std::fprintf(out_, "  %-14s %10.2f s %6.1f %%\n", phase, seconds, t.wall > 0 ? 100 * seconds / t.wall : 0.0);
  std::fflush(out_);
}

}  // namespace lagfsi
