// Regression of the coupled cases (fsi/): each case file at CI size against its reference, with the
// tolerances stated in the case README (the values reached where the reference is not met).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "fluid_checks.hpp"

namespace {

using namespace lagfsi::testing;

/// Every coupled step converged to the interface tolerance; returns the mean FSI iterations per coupled step.
double check_coupling(const RunResult& r, int min_coupled_steps) {
  const auto s = summary_of(r);
  EXPECT_EQ(s["status"], "completed");
  EXPECT_GE(s["coupling"]["coupled_steps"].get<int>(), min_coupled_steps);
  EXPECT_LE(s["coupling"]["residual_max"].get<double>(), 1e-6);
  return s["coupling"]["iterations_mean"].get<double>();
}

/// Reference series (time, value) from a CSV; `component` and `source` keep the rows with those labels (label
/// columns of the same names).
std::vector<std::pair<double, double>> reference(const std::string& rel, const std::string& tcol,
                                                 const std::string& vcol, const std::string& component = "",
                                                 const std::string& source = "") {
  const Csv c = read_csv(fs::path(LAGFSI_SOURCE_DIR) / rel);
  std::vector<std::pair<double, double>> out;
  for (size_t i = 0; i < c.rows(); ++i)
    if ((component.empty() || c.text.at("component")[i] == component) &&
        (source.empty() || c.text.at("source")[i] == source))
      out.push_back({c[tcol][i], c[vcol][i]});
  EXPECT_FALSE(out.empty()) << rel;
  return out;
}

double rms_against(const Csv& c, const std::string& col, const std::vector<std::pair<double, double>>& ref,
                   double t_max) {
  double e2 = 0;
  int n = 0;
  for (const auto& [t, v] : ref) {
    if (t > t_max) continue;
    const double s = interp(c["time"], c[col], t);
    EXPECT_FALSE(std::isnan(s)) << col << " at t = " << t;
    e2 += (s - v) * (s - v);
    ++n;
  }
  return n ? std::sqrt(e2 / n) : std::nan("");
}

/// The flexible tank's run (with `sets`) against beam theory; returns the mean FSI iterations per coupled step.
double check_flexible_tank(const std::string& name, const std::vector<std::string>& sets) {
  // Avancini (2018) sec. 7.3.1, monolithic PSPG fluid, matching interface, IQN-IMVJ, 1 s. No digitized reference: the
  // wall must oscillate about its static deflection under the water load, 9.77 mm by beam theory (README), up to the
  // amplification by the plate's own weight (P-delta, at most 1.35) and the drop of the water level as the wall leans:
  // the mean after the start-up lies in [1.0, 1.3] x 9.77 mm (measured 11.1 mm). The first overshoot, about twice the
  // static value for a suddenly applied load, lies in [1.8, 2.8] x 9.77 mm (measured 23.3 mm at 0.169 s).
  std::vector<std::string> all = {"output.every=50"};
  all.insert(all.end(), sets.begin(), sets.end());
  const auto r = run_case_1thread("cases/flexible_tank/case.json", name, all);
  const Csv c = probes_of(r);
  EXPECT_GT(c.rows(), 900u);
  if (c.rows() <= 900u) return 1e30;
  const double w = 9.77e-3;
  double mean = 0, first_peak = 0;
  int n = 0;
  for (size_t i = 0; i < c.rows(); ++i) {
    if (c["time"][i] <= 0.3) first_peak = std::max(first_peak, c["tip_ux"][i]);
    if (c["time"][i] >= 0.2) {
      mean += c["tip_ux"][i];
      ++n;
    }
  }
  mean /= n;
  EXPECT_GT(mean, 1.0 * w);
  EXPECT_LT(mean, 1.3 * w);
  EXPECT_GT(first_peak, 1.8 * w);
  EXPECT_LT(first_peak, 2.8 * w);
  EXPECT_LE(max_area_drift(c), 0.01);
  return check_coupling(r, 1000);
}

TEST(FlexibleTank, OscillatesAboutTheStaticDeflection) {
  EXPECT_LE(check_flexible_tank("fsi_flexible_tank", {}), 5.0)
      << "IQN-IMVJ iterations per coupled step (measured 3.98)";
}

TEST(FlexibleTank, TheSameUnderNewmark) {
  // The default is generalized-alpha (rho_inf = 0.8: the analysis' default with a Robin fluid). Before it could
  // be, two defects had to go: the fluid wrote the structure's velocity and acceleration at t_{n+1} into its
  // ghost particles among the other particles' values at t_{n+1-af} (TimeIntegrator::evaluation): the pressure
  // at the plate grew step after step and a plate element turned over at 0.19 s; then water went into the
  // plate at its waterline from 0.57 s, between two ghost particles (a fluid particle on a structure's face now
  // goes as one pressed against a ghost): 9.6 % of the water by 1 s. The default's run is the test above
  // (measured: mean 1.145 of beam theory, first peak 23.36 mm, largest area drift 0.05 %, 3.98 iterations). The
  // trapezoidal rule (measured: the same mean and peak, 0.05 %, 4.03 iterations) keeps its own run.
  EXPECT_LE(check_flexible_tank("fsi_flexible_tank_newmark", {R"(analysis.integrator={"type": "newmark"})"}), 5.0);
}

TEST(ElasticObstacleWalhorn, PeakDeflectionMatchesIdelsohn2008) {
  // Dam break onto the elastic obstacle, fractional-step fluid (inverted elements left to the remesh),
  // non-matching interface, IQN-IMVJ with the force predictor; 0.45 s covers the impact and the first
  // swing. Against the PFEM of Idelsohn et al. 2008: peak 48.3 mm at 0.260 s (measured 48.4 mm at 0.231 s)
  // within 10 % and 0.04 s; RMS difference over 0-0.45 s <= 8 mm (measured 3.0 mm; over the whole
  // reference, 0-0.69 s, 8.6 mm). Against each of the three other published solutions (Bogaers et al. 2016,
  // Liu et al. 2013, Sun et al. 2019) over 0-0.45 s: <= 6 mm (measured 4.3 / 2.4 / 4.0 mm; the four published
  // solutions are 3.5-5.3 mm from the mean of the others). Iterations: the target is at most 5 per
  // coupled step (measured 4.04 over 0.45 s, 4.09 over 1 s).
  const auto r = run_case_1thread("cases/elastic_obstacle_walhorn/case.json", "fsi_walhorn",
                                  {"analysis.end_time=0.45", "output.every=50"});
  const Csv c = probes_of(r);
  const auto ref =
      reference("cases/elastic_obstacle_walhorn/reference/idelsohn_2008_pfem_tip_ux.csv", "time", "tip_ux");
  double peak = 0, t_peak = 0;
  for (size_t i = 0; i < c.rows(); ++i)
    if (c["tip_ux"][i] > peak) {
      peak = c["tip_ux"][i];
      t_peak = c["time"][i];
    }
  // Bounds: the published solutions' own spread, as the README and expected.json state it: peaks
  // 45.0-48.3 mm at 0.217-0.260 s (the peak within 2.5 % above the largest), and 3.5-5.3 mm RMS among
  // themselves over 0-0.45 s.
  EXPECT_GE(peak, 0.045);
  EXPECT_LE(peak, 0.0495);
  EXPECT_GE(t_peak, 0.217);
  EXPECT_LE(t_peak, 0.260);
  EXPECT_LE(rms_against(c, "tip_ux", ref, 0.45), 0.0053);
  const std::string others = "cases/elastic_obstacle_walhorn/reference/walhorn_numerical_tip_ux.csv";
  for (const std::string src : {"bogaers_2016", "liu_2013", "sun_2019"})
    EXPECT_LE(rms_against(c, "tip_ux", reference(others, "time", "tip_ux", "", src), 0.45), 0.0053) << src;
  EXPECT_LE(check_coupling(r, 250), 5.0) << "IQN-IMVJ iterations per coupled step";
}

TEST(ElasticGateAntoci, OpensLikeTheExperimentAndFollowsThePublishedSolutions) {
  // Rubber gate released by the water, fractional-step fluid, non-matching interface, IQN-IMVJ, 0.2 s.
  // Against the experiment of Antoci et al. 2007: the free end's horizontal displacement within 4 mm at
  // 0.04 and 0.08 s (measured 2.2 and 2.4 mm); after its peak at 0.1 s the gate closes again while the
  // experiment's stays open, as in the three published solutions with the same constants (README), so over the
  // experiment's points of 0-0.2 s the RMS errors are only held at what this version reaches: x <= 9 mm
  // (measured 8.2), y <= 7.5 mm (measured 6.2). Against each published solution (Khayyer et al. 2018, Yang
  // et al. 2012, Ng et al. 2020) over their points of 0-0.2 s: x <= 6 mm (measured 4.3 / 2.5 / 2.2 mm; the
  // three differ from one another by up to 3.2 mm), and y of the end's downstream corner (the point those
  // solutions report; the upstream corner is t sin(theta) ~ 3 mm lower) <= 3.5 mm (2.3 / 1.5 / 1.4 mm). A
  // gate of half the stiffness, which follows the experiment better, is 6.2 / 6.3 mm from two of them in x
  // over the same points (7.2 mm over 0.4 s), so the bound tells the two apart, if narrowly.
  const auto r = run_case_1thread("cases/elastic_gate_antoci/case.json", "fsi_antoci",
                                  {"analysis.end_time=0.2", "output.every=100"});
  const Csv c = probes_of(r);
  const std::string rel = "cases/elastic_gate_antoci/reference/antoci_2007_experiment_tip_displacement.csv";
  const auto rx = reference(rel, "time", "displacement", "x");
  const auto ry = reference(rel, "time", "displacement", "y");
  for (const auto& [t, v] : rx) {
    if (t < 0.1) {
      EXPECT_NEAR(interp(c["time"], c["tip_ux"], t), v, 0.004) << "t = " << t;
    }
  }
  EXPECT_LE(rms_against(c, "tip_ux", rx, 0.2), 0.009);
  EXPECT_LE(rms_against(c, "tip_uy", ry, 0.2), 0.0075);
  const std::string num = "cases/elastic_gate_antoci/reference/antoci_gate_numerical_tip_displacement.csv";
  for (const std::string src : {"khayyer_2018", "yang_2012", "ng_2020"}) {
    EXPECT_LE(rms_against(c, "tip_ux", reference(num, "time", "displacement", "x", src), 0.2), 0.006) << src;
    EXPECT_LE(rms_against(c, "tip_right_uy", reference(num, "time", "displacement", "y", src), 0.2), 0.0035) << src;
  }
  EXPECT_LE(check_coupling(r, 390), 5.5) << "IQN-IMVJ iterations per coupled step (measured 4.67 over 0.4 s)";
}

}  // namespace

TEST(TurekHronFsi1, TheShellFlagMeetsTheWaterAsTheTrianglesFlagDoes) {
  // cases/turek_hron_fsi1/case_shell.json (the flag as 10 cubic shell elements, its faces the interface) against
  // case.json (T10 triangles) over the first 0.3 s of the inflow's ramp, while the accelerating flow presses the
  // flag's end (-4.7 N/m on it at 0.3 s) and starts to bend it (21 micrometres): the fluid sees the same flag, so the
  // forces on it and its deflection agree (measured at 0.3 s: drag -4.740 and -4.657 N/m, u_y(A) -21.4 and -21.1
  // micrometres). u_x(A) does not: the pressure (about 300 Pa in the ramp) on its faces lengthens the plane-strain
  // triangles by nu (1 + nu) p L / E, which the shell's uncoupled law leaves out (-4 and -66 micrometres).
  const std::vector<std::string> sets = {"analysis.end_time=0.3", "output.vtk=false"};
  const RunResult t = run_case_file("cases/turek_hron_fsi1/case.json", "fsi_turek_hron_fsi1_t10", sets);
  const RunResult s = run_case_file("cases/turek_hron_fsi1/case_shell.json", "fsi_turek_hron_fsi1_shell", sets);
  ASSERT_EQ(t.exit_code, 0) << t.stderr_text;
  ASSERT_EQ(s.exit_code, 0) << s.stderr_text;
  const Csv pt = read_csv(t.out_dir / "probes.csv"), ps = read_csv(s.out_dir / "probes.csv");
  EXPECT_NEAR(at_time(ps, "drag_flag", 0.3), at_time(pt, "drag_flag", 0.3),
              0.03 * std::abs(at_time(pt, "drag_flag", 0.3)));
  EXPECT_NEAR(at_time(ps, "tip_uy", 0.3), at_time(pt, "tip_uy", 0.3), 0.05 * std::abs(at_time(pt, "tip_uy", 0.3)));
  EXPECT_LT(at_time(ps, "tip_ux", 0.3), at_time(pt, "tip_ux", 0.3) - 3e-5);
}
