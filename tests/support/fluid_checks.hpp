#pragma once
// Checks shared by the fluid regression tests (both schemes): runs of the case files and the measures the
// case READMEs quote (front errors against Koshizuka & Oka and Martin & Moyce, sloshing periods, area drift).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "case_runner.hpp"

namespace lagfsi::testing {

/// One OpenMP thread (as ctest sets, also when a test binary runs by hand): a fixed summation order keeps the
/// remeshed runs, which are sensitive to round-off, reproducible.
inline RunResult run_case_1thread(const std::string& case_rel, const std::string& tag,
                                  const std::vector<std::string>& sets = {}) {
  return run_case_file(case_rel, tag, sets, "--threads 1");
}

/// Linear interpolation of ys(xs) at x; NaN outside [xs.front(), xs.back()].
inline double interp(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (xs.empty() || x < xs.front() || x > xs.back()) return std::nan("");
  size_t i = 1;
  while (i + 1 < xs.size() && xs[i] < x) ++i;
  const double s = xs[i] > xs[i - 1] ? (x - xs[i - 1]) / (xs[i] - xs[i - 1]) : 0.0;
  return ys[i - 1] + s * (ys[i] - ys[i - 1]);
}

/// Martin & Moyce (1952), a = 2.25 in: RMS error of the front Z = x/a (T = t sqrt(2g/a) <= 3) and of the column
/// height H = h/(2a) (tau = t sqrt(g/a), all table points the run covers). Every surge point with T <= 3 must
/// be covered.
struct MartinMoyceErrors {
  double front_rms = 0, height_rms = 0;
  int front_points = 0, height_points = 0;
};

inline MartinMoyceErrors martin_moyce_errors(const Csv& c) {
  const double a = 0.05715, g = 9.81;
  std::vector<double> T, Z, tau, H;
  for (size_t i = 0; i < c.rows(); ++i) {
    T.push_back(c["time"][i] * std::sqrt(2 * g / a));
    tau.push_back(c["time"][i] * std::sqrt(g / a));
    Z.push_back(c["front_x"][i] / a);
    H.push_back(c["column_height"][i] / (2 * a));
  }
  const Csv ref =
      read_csv(fs::path(LAGFSI_SOURCE_DIR) / "cases/dam_break_floor/reference/martin_moyce_1952_tables_2_6.csv");
  EXPECT_GT(ref.rows(), 0u);
  MartinMoyceErrors e;
  double sf = 0, sh = 0;
  for (size_t k = 0; k < ref.rows(); ++k) {
    const std::string& series = ref.text.at("series")[k];
    const double tn = ref["time_nondim"][k], v = ref["value"][k];
    if (series == "surge" && tn <= 3.0) {
      const double z = interp(T, Z, tn);
      EXPECT_FALSE(std::isnan(z)) << "the run does not cover T = " << tn;
      if (std::isnan(z)) continue;
      sf += (z - v) * (z - v);
      ++e.front_points;
    } else if (series == "height") {
      const double hh = interp(tau, H, tn);
      if (std::isnan(hh)) continue;
      sh += (hh - v) * (hh - v);
      ++e.height_points;
    }
  }
  e.front_rms = e.front_points ? std::sqrt(sf / e.front_points) : 1e9;
  e.height_rms = e.height_points ? std::sqrt(sh / e.height_points) : 1e9;
  return e;
}

inline double max_area_drift(const Csv& c) {
  const double a0 = c["fluid_area"].front();
  double m = 0;
  for (double a : c["fluid_area"]) m = std::max(m, std::abs(a / a0 - 1));
  return m;
}

/// The hydrostatic case's checks: at every sample the bottom pressure within 1 % of rho g H, the
/// kinetic energy that of speeds below 1e-3 sqrt(g H), the fluid area within 0.1 %; the run reaches 1 s.
inline void check_hydrostatic(const Csv& c) {
  const double rho = 1000, g = 9.81, H = 0.2, area0 = c["fluid_area"].front();
  const double vmax = 1e-3 * std::sqrt(g * H);
  for (size_t i = 0; i < c.rows(); ++i) {
    EXPECT_NEAR(c["p_bottom"][i], rho * g * H, 0.01 * rho * g * H) << "t " << c["time"][i];
    EXPECT_LT(c["kinetic_energy"][i], 0.5 * rho * area0 * vmax * vmax) << "t " << c["time"][i];
    EXPECT_NEAR(c["fluid_area"][i], area0, 1e-3 * area0) << "t " << c["time"][i];
  }
  EXPECT_NEAR(c["time"].back(), 1.0, 1e-9);
}

/// Koshizuka & Oka (1996) dam break (L = 0.146 m, h = 0.0073 m): RMS error of the front Z = x/L against the
/// digitized experiment (cases/dam_break_tank/reference, pysph file) up to Z = 4 (the wall), and the time the
/// front comes within 1.5 h of the right wall (-1 if it does not).
inline std::pair<double, double> dam_break_tank_front(const Csv& c) {
  const double L = 0.146, g = 9.81;
  const Csv ref =
      read_csv(fs::path(LAGFSI_SOURCE_DIR) / "cases/dam_break_tank/reference/koshizuka_oka_1996_surge_front_pysph.csv");
  std::vector<double> Z;
  for (double x : c["front_x"]) Z.push_back(x / L);
  double sum2 = 0;
  int n = 0;
  for (size_t k = 0; k < ref.rows(); ++k) {
    const double T = ref["T"][k], Zr = ref["Z"][k];
    if (Zr >= 4.0) continue;
    const double z = interp(c["time"], Z, T / std::sqrt(2 * g / L));
    EXPECT_FALSE(std::isnan(z)) << "the run does not cover T = " << T;
    sum2 += (z - Zr) * (z - Zr);
    ++n;
  }
  double t_impact = -1;
  for (size_t i = 0; i < c.rows(); ++i)
    if (c["front_x"][i] >= 4 * L - 1.5 * 0.0073) {
      t_impact = c["time"][i];
      break;
    }
  return {n ? std::sqrt(sum2 / n) : 1e9, t_impact};
}

/// First sloshing mode of a tank of length L with water depth d: omega^2 = g k tanh(k d), k = pi / L.
inline double linear_sloshing_period(double L, double d) {
  const double k = std::numbers::pi / L;
  return 2 * std::numbers::pi / std::sqrt(9.81 * k * std::tanh(k * d));
}

/// Mean period of the upward crossings of level d by the column `col` (0 if fewer than two crossings).
inline double sloshing_period(const Csv& c, const std::string& col, double d) {
  std::vector<double> ups;
  const auto& t = c["time"];
  const auto& e = c[col];
  for (size_t i = 1; i < t.size(); ++i)
    if (e[i - 1] < d && e[i] >= d) ups.push_back(t[i - 1] + (d - e[i - 1]) / (e[i] - e[i - 1]) * (t[i] - t[i - 1]));
  return ups.size() < 2 ? 0.0 : (ups.back() - ups.front()) / static_cast<double>(ups.size() - 1);
}

/// The viscous sloshing case at CI size (cases/sloshing_viscous, h = 0.015 m, 2 s): stable, area drift <= 1 %,
/// kinetic energy of 1.5-2 s below a quarter of that of 0-0.5 s, first period within 3 % of linear theory.
/// Returns (kinetic energy ratio, period, linear period).
inline std::tuple<double, double, double> check_sloshing_viscous(const Csv& c) {
  EXPECT_NEAR(c["time"].back(), 2.0, 1e-9);
  EXPECT_LE(max_area_drift(c), 0.01);
  double ke_early = 0, ke_late = 0;
  for (size_t i = 0; i < c.rows(); ++i) {
    const double t = c["time"][i], k = c["kinetic_energy"][i];
    EXPECT_TRUE(std::isfinite(k)) << "t " << t;
    if (t < 0.5) ke_early = std::max(ke_early, k);
    if (t >= 1.5) ke_late = std::max(ke_late, k);
  }
  EXPECT_GT(ke_early, 1.0);
  EXPECT_LT(ke_late, 0.25 * ke_early) << "kinetic energy must decay";
  // Period from the maxima of the elevation next to the left wall after the release transient: a maximum
  // is the largest value within +-0.15 s (a quarter period or less), so that the probe's steps of a fraction of a
  // millimetre (a surface particle passing x) on a rising flank are not taken for crests.
  const auto& t = c["time"];
  const auto& e = c["eta_left"];
  std::vector<double> peaks;
  for (size_t i = 0; i < c.rows(); ++i) {
    if (t[i] <= 0.5 || e[i] <= 0.252 || (!peaks.empty() && t[i] - peaks.back() <= 0.4)) continue;
    bool top = true;
    for (size_t j = 0; j < c.rows() && top; ++j)
      if (std::abs(t[j] - t[i]) <= 0.15 && e[j] > e[i]) top = false;
    if (top && t[i] + 0.15 <= t.back()) peaks.push_back(t[i]);
  }
  EXPECT_GE(peaks.size(), 2u);
  if (peaks.size() < 2) return {ke_late / ke_early, 0.0, 0.0};
  const double period = (peaks.back() - peaks.front()) / static_cast<double>(peaks.size() - 1);
  const double k1 = std::numbers::pi / 0.5;
  const double T_lin = 2 * std::numbers::pi / std::sqrt(9.81 * k1 * std::tanh(k1 * 0.25));
  EXPECT_NEAR(period, T_lin, 0.03 * T_lin);
  return {ke_late / ke_early, period, T_lin};
}

}  // namespace lagfsi::testing

namespace lagfsi::testing {

/// Shaken tank (cases/sloshing_forced): RMS error of the elevation probe `col` (eta_left | eta_right) against
/// the linear modal solution (reference/linear_modal_solution.csv) over t <= t_end, relative to the largest
/// linear elevation there.
inline double shaken_tank_error(const Csv& c, const std::string& col, double t_end) {
  const Csv ref = read_csv(fs::path(LAGFSI_SOURCE_DIR) / "cases/sloshing_forced/reference/linear_modal_solution.csv");
  double e2 = 0, peak = 0;
  int n = 0;
  for (size_t k = 0; k < ref.rows(); ++k)
    if (ref["time"][k] <= t_end) peak = std::max(peak, std::abs(ref[col][k]));
  for (size_t i = 0; i < c.rows(); ++i) {
    if (c["time"][i] > t_end) continue;
    const double lin = interp(ref["time"], ref[col], c["time"][i]);
    EXPECT_TRUE(std::isfinite(c[col][i])) << col << " at t " << c["time"][i];
    e2 += std::pow(c[col][i] - 0.5 - lin, 2);
    ++n;
  }
  return n && peak > 0 ? std::sqrt(e2 / n) / peak : 1e9;
}

}  // namespace lagfsi::testing
