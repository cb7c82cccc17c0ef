// Regression of the shell (positional frame) versions of the FSI cases against the same cases with the wall
// meshed by T10 continuum elements (target: tip histories within 3 % of the peak), and of a shell that
// separates two fluid regions (they must stay apart: no fluid element may cross it).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "fluid_checks.hpp"

namespace {

using namespace lagfsi::testing;

/// Largest |a - b| over the times of `a` (b interpolated: a step retried with a halved dt adds rows to one
/// run only), relative to the peak |a|.
double max_difference_over_peak(const Csv& a, const Csv& b, const std::string& col, double* peak_out = nullptr) {
  EXPECT_GT(a.rows(), 10u);
  double peak = 0, worst = 0;
  for (size_t i = 0; i < a.rows(); ++i) {
    const double vb = interp(b["time"], b[col], a["time"][i]);
    EXPECT_FALSE(std::isnan(vb)) << "t = " << a["time"][i];
    peak = std::max(peak, std::abs(a[col][i]));
    worst = std::max(worst, std::abs(a[col][i] - vb));
  }
  if (peak_out) *peak_out = peak;
  return worst / peak;
}

Csv completed(const RunResult& r) {
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto s = summary_of(r);
  EXPECT_EQ(s["status"], "completed");
  EXPECT_LE(s["coupling"]["residual_max"].get<double>(), 1e-6);
  return read_csv(r.out_dir / "probes.csv");
}

/// Runs a case with its T10 wall and with its shell wall (same overrides); returns max |shell - T10| of the
/// tip's x displacement over the T10 peak, which `peak` receives.
double shell_against_t10(const std::string& name, const std::vector<std::string>& sets, double& peak) {
  const Csv t10 = completed(run_case_1thread("cases/" + name + "/case.json", "shell_t10_" + name, sets));
  const Csv sh = completed(run_case_1thread("cases/" + name + "_shell/case.json", "shell_" + name, sets));
  const double d = max_difference_over_peak(t10, sh, "tip_ux", &peak);
  std::printf("%s: peak %.5f m, max |shell - T10| / peak = %.4f\n", name.c_str(), peak, d);
  return d;
}

TEST(FlexibleTankShell, TipHistoryWithinThreePercentOfTheT10Wall) {
  // Fractional-step fluid, 0.3 s (the first overshoot and trough); the full monolithic second is in the
  // case README (1.6 % of the peak with IQN-IMVJ, 0.5 % RMS).
  const std::vector<std::string> sets{"analysis.end_time=0.3", "bodies.0.scheme.type=fractional_step",
                                      "output.every=100"};
  double peak = 0;
  const double d = shell_against_t10("flexible_tank", sets, peak);
  EXPECT_GT(peak, 0.015);
  EXPECT_LT(d, 0.03);
}

TEST(ElasticGateAntociShell, TipHistoryWithinFourPercentOfTheT10Gate) {
  // The opening, to the largest opening (0.11 s) and a little after, 0.12 s: the shell's SVK-type law
  // against the T10 gate's neo-Hookean law (both E = 12 MPa, nu = 0.4, plane strain); measured 3.5 % of
  // the peak (2.0 % with the "source" volume correction of the fluid, which lets the area drift by 1.4 %;
  // the fluid's correction alone moves each gate's tip by 1-2 % of the peak). Later, as the gate closes onto the
  // falling water, the case itself is sensitive: two shell runs that differ by round-off (the same element computed in
  // another order) part by 6 % of the peak at 0.2 s, and T10 runs with the svk and neo-Hookean laws by 5 % over 0.4 s
  // (README).
  const std::vector<std::string> sets{"analysis.end_time=0.12", "output.every=100"};
  double peak = 0;
  const double d = shell_against_t10("elastic_gate_antoci", sets, peak);
  EXPECT_GT(peak, 0.035);
  EXPECT_LT(d, 0.04);
}

TEST(BaffleShell, KeepsTwoFluidRegionsApart) {
  // A flexible baffle (shell, clamped at the floor) between water 0.1 m deep on its left and 0.04 m on its
  // right, wet on both faces and at its tip. Had fluid leaked past it, the right level would rise towards
  // the common level 0.07 m within the run; it must stay near 0.04 m, the left one near 0.1 m (it drops as
  // the baffle leans: about 0.09 m), and the area must be kept within 1 %.
  const fs::path dir = fresh_dir("shell_baffle");
  const nlohmann::json c = nlohmann::json::parse(R"({
    "name": "baffle_shell",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.5, "newton": {"max_iterations": 25}},
    "gravity": [0.0, -9.81],
    "bodies": [
      {"name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.005, "alpha": 1.2,
       "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.097, 0.1]},
                   {"type": "rectangle", "origin": [0.103, 0], "size": [0.097, 0.04]}],
       "walls": [{"name": "tank", "points": [[0, 0.2], [0, 0], [0.2, 0], [0.2, 0.2]]}],
       "scheme": {"type": "fractional_step"}},
      {"name": "baffle", "type": "shell",
       "material": {"type": "svk", "young": 5e7, "poisson": 0.0, "density": 1500.0},
       "thickness": 0.004, "geometry": {"type": "line", "from": [0.1, 0], "to": [0.1, 0.12]},
       "mesh": {"elements": 6, "order": 3},
       "boundary_conditions": [{"type": "fixed", "select": {"type": "point", "at": [0.1, 0]}}]}
    ],
    "couplings": [{"type": "dirichlet_neumann", "name": "fsi", "fluid": "water", "structure": "baffle",
                   "interface": {"type": "all"}, "ghost_spacing": 0.005,
                   "acceleration": {"type": "iqn_ils", "reuse_steps": 2}, "tolerance": 1e-6}],
    "probes": [
      {"name": "tip_ux", "type": "displacement", "body": "baffle", "at": [0.1, 0.12], "component": "x"},
      {"name": "h_left", "type": "elevation", "body": "water", "x": 0.05},
      {"name": "h_right", "type": "elevation", "body": "water", "x": 0.15},
      {"name": "area", "type": "fluid_area", "body": "water"}
    ],
    "output": {"every": 100}
  })");
  const Csv p = completed(run_case_text(dir, c.dump(2), "--quiet --threads 1"));
  ASSERT_GT(p.rows(), 400u);
  double right_max = 0, left_min = 1, tip_max = 0;
  for (size_t i = 0; i < p.rows(); ++i) {
    right_max = std::max(right_max, p["h_right"][i]);
    left_min = std::min(left_min, p["h_left"][i]);
    tip_max = std::max(tip_max, std::abs(p["tip_ux"][i]));
  }
  const double mean_right = mean_between(p, "h_right", 0.25, 0.5), mean_left = mean_between(p, "h_left", 0.25, 0.5);
  const double drift = p["area"].back() / p["area"].front() - 1.0;
  std::printf("baffle: right level max %.4f (mean %.4f), left level min %.4f (mean %.4f), tip %.4f m, area %+.2f %%\n",
              right_max, mean_right, left_min, mean_left, tip_max, 100 * drift);
  EXPECT_GT(tip_max, 0.005);  // the baffle does bend under the difference of levels
  EXPECT_LT(right_max, 0.045);
  EXPECT_NEAR(mean_right, 0.04, 0.003);
  EXPECT_GT(mean_left, 0.085);
  EXPECT_LT(std::abs(drift), 0.01);
}

}  // namespace
