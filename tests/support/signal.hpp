#pragma once
// Signal statistics for regression checks (the same definitions as cases/tools/lagfsi_post.py).
#include <algorithm>
#include <optional>
#include <vector>

namespace lagfsi::testing {

struct PeriodicStats {
  double mean, amplitude, frequency;
  int periods;
};

/// Turek & Hron's convention: mean = (max + min)/2, amplitude = (max - min)/2 over the last full period;
/// frequency from the mean spacing of upward crossings of the mid-level (with hysteresis).
inline std::optional<PeriodicStats> periodic_stats(const std::vector<double>& t, const std::vector<double>& u) {
  if (u.size() < 3) return std::nullopt;
  const double hi = *std::max_element(u.begin(), u.end()), lo = *std::min_element(u.begin(), u.end());
  const double mid = 0.5 * (hi + lo), band = 0.1 * (hi - lo);
  std::vector<double> ups;
  bool armed = false;
  for (size_t i = 1; i < u.size(); ++i) {
    if (u[i] < mid - band) armed = true;
    if (armed && u[i - 1] < mid && mid <= u[i]) {
      ups.push_back(t[i - 1] + (mid - u[i - 1]) / (u[i] - u[i - 1]) * (t[i] - t[i - 1]));
      armed = false;
    }
  }
  if (ups.size() < 2) return std::nullopt;
  double umax = -1e300, umin = 1e300;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] >= ups[ups.size() - 2] && t[i] <= ups.back()) {
      umax = std::max(umax, u[i]);
      umin = std::min(umin, u[i]);
    }
  const double period = (ups.back() - ups.front()) / static_cast<double>(ups.size() - 1);
  return PeriodicStats{0.5 * (umax + umin), 0.5 * (umax - umin), 1.0 / period, static_cast<int>(ups.size() - 1)};
}

}  // namespace lagfsi::testing
