// Regression: the solid cases of cases/ at CI size against their references (analytic values computed
// here from the case parameters, or the published tables shipped in cases/<case>/reference/).
// Tolerances are the targets set when each case was added; the measured errors are far smaller
// (see each case's README), so a failure means a real change of behaviour.
#include <gtest/gtest.h>

#include <cmath>

#include "case_runner.hpp"
#include "signal.hpp"

namespace {

using namespace lagfsi::testing;

double rel_err(double value, double ref) { return std::abs(value / ref - 1.0); }

// ---------------------------------------------------------------- cantilever_step_load (Avancini 2018, 5.5.1)
// Timoshenko: delta = P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6, G = E/2 (nu = 0), b = 1 m.
double cantilever_timoshenko() {
  const double E = 210e9, L = 1.2, h = 0.18566, P = 5e6, I = h * h * h / 12.0, A = h;
  return P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * 0.5 * E * A);
}

// Bounds are the agreements the case READMEs state (cases/<case>/expected.json); where this file runs a
// reduced size, the full size is checked by the `cases` tier (ctest -L cases).
TEST(CantileverStepLoad, StaticWithinHalfAPercentOfTimoshenko) {
  const Csv c = probes_of(run_case_file("cases/cantilever_step_load/case.json", "cantilever_static",
                                        {"analysis.type=static", "analysis.load_steps=1"}));
  const double tip = -c["tip_uy_axis"].back();
  EXPECT_LT(rel_err(tip, cantilever_timoshenko()), 0.005) << "tip " << tip;  // README: +0.3 %, within 0.5 %
  // Equilibrium: the reaction at the clamp balances the load.
  EXPECT_NEAR(c["reaction_y"].back(), 5e6, 5e6 * 1e-6);
}

TEST(CantileverStepLoad, UndampedPeakIsTwiceStatic) {
  const Csv c = probes_of(
      run_case_file("cases/cantilever_step_load/case.json", "cantilever_undamped", {"analysis.end_time=0.0125"}));
  const auto& u = c["tip_uy_axis"];
  const double peak = -*std::min_element(u.begin(), u.end());
  EXPECT_LT(rel_err(peak, 2 * cantilever_timoshenko()), 0.005) << "peak " << peak;  // README: within 0.5 %
  // Energy: Newmark (1/4, 1/2) conserves E_kin + E_strain - W_ext for this step load.
  double emax = 0, bmax = 0;
  for (size_t i = 0; i < c.rows(); ++i) {
    emax = std::max(emax, std::abs(c["energy_total"][i]));
    bmax = std::max(bmax, std::abs(c["energy_balance"][i]));
  }
  EXPECT_LT(bmax, 0.005 * emax);
}

TEST(CantileverStepLoad, DampedSettlesOnStatic) {
  const Csv c = probes_of(
      run_case_file("cases/cantilever_step_load/case.json", "cantilever_damped", {"bodies.0.damping.mass=200"}));
  EXPECT_LT(rel_err(-c["tip_uy_axis"].back(), cantilever_timoshenko()), 0.02) << c["tip_uy_axis"].back();
}

// ---------------------------------------------------------------- clamped_beam_nonlinear (Avancini 2018, 5.5.2)
TEST(ClampedBeamNonlinear, LinearStaticMatchesBeamTheory) {
  // A load 1000x smaller than the case's keeps the response linear: delta = P L^3 / (192 E I).
  const double P = 0.64, L = 20, E = 30e6, I = 0.125 * 0.125 * 0.125 / 12.0;
  const Csv c =
      probes_of(run_case_file("cases/clamped_beam_nonlinear/case.json", "clamped_linear",
                              {"analysis.type=static", "analysis.load_steps=1", "bodies.0.loads.0.value=[0,-0.64]"}));
  const double expected = P * L * L * L / (192 * E * I);
  EXPECT_NEAR(expected, 5.4613e-3, 1e-6);  // Avancini (2018) sec. 5.5.2's number, scaled by 1/1000
  EXPECT_LT(rel_err(-c["mid_uy"].back(), expected), 0.002) << c["mid_uy"].back();  // README: within 0.2 %
}

TEST(ClampedBeamNonlinear, NonlinearAmplitudeAboutSevenPercentOfLinear) {
  // First peak (about 1.1 ms): Avancini (2018) reports the nonlinear amplitude is about 7 % of the linear one
  // (linear dynamic peak = 2 x 5.4613 in). The README states 7.0 %, within 5 % of Avancini's 7 %.
  const Csv c = probes_of(
      run_case_file("cases/clamped_beam_nonlinear/case.json", "clamped_nonlinear", {"analysis.end_time=1.5e-3"}));
  const auto& u = c["mid_uy"];
  const double ratio = -*std::min_element(u.begin(), u.end()) / (2 * 5.4613);
  EXPECT_GT(ratio, 0.07 * 0.95);
  EXPECT_LT(ratio, 0.07 * 1.05);
}

// ---------------------------------------------------------------- elastica_mattiasson
TEST(ElasticaMattiasson, TipWithinThreeHundredthsOfAPercentOfTable) {
  expect_tip_matches_mattiasson(probes_of(run_case_file("cases/elastica_mattiasson/case.json", "elastica")),
                                "cases/elastica_mattiasson", 3e-4);  // README: within 0.03 %
}

// ---------------------------------------------------------------- Turek & Hron CSM1 / CSM3
struct TurekRef {
  double mean, amplitude, frequency;
};
TurekRef turek(const std::string& case_name, const std::string& quantity) {
  // The reference CSV has text columns; read it by hand.
  std::ifstream in(fs::path(LAGFSI_SOURCE_DIR) / "cases/turek_csm1/reference/turek_hron_2006_reference_values.csv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(case_name + "," + quantity + ",", 0) != 0) continue;
    std::stringstream ss(line);
    std::string f[5];
    for (auto& s : f) std::getline(ss, s, ',');
    return {std::stod(f[2]), f[3].empty() ? 0.0 : std::stod(f[3]), f[4].empty() ? 0.0 : std::stod(f[4])};
  }
  throw std::runtime_error("no reference for " + case_name + " " + quantity);
}

TEST(TurekCsm1, StaticTipWithinFiveHundredthsOfAPercent) {
  const Csv c = probes_of(run_case_file("cases/turek_csm1/case.json", "csm1"));
  // README: within 0.05 % (-0.03 %, -0.02 %).
  EXPECT_LT(rel_err(c["tip_ux"].back(), turek("CSM1", "ux_A").mean), 5e-4) << c["tip_ux"].back();
  EXPECT_LT(rel_err(c["tip_uy"].back(), turek("CSM1", "uy_A").mean), 5e-4) << c["tip_uy"].back();
}

TEST(TurekCsm3, MeanAmplitudeFrequency) {
  // CI size: dt = 0.01 s over 5 s (about 5 periods); the full case uses dt = 0.005 s over 10 s, and the `cases` tier
  // checks it against the README's agreement (0.05 % on mean and amplitude, 0.6 % on the frequency). At this size
  // the bounds are the original targets (2 %, 1 %): the coarser step lengthens the period.
  const Csv c =
      probes_of(run_case_file("cases/turek_csm3/case.json", "csm3", {"analysis.dt=0.01", "analysis.end_time=5.0"}));
  for (const auto& [col, q] : {std::pair{"tip_ux", "ux_A"}, std::pair{"tip_uy", "uy_A"}}) {
    const auto s = periodic_stats(c["time"], c[col]);
    ASSERT_TRUE(s.has_value());
    const TurekRef r = turek("CSM3", q);
    EXPECT_LT(rel_err(s->mean, r.mean), 0.02) << col << " mean " << s->mean;
    EXPECT_LT(rel_err(s->amplitude, r.amplitude), 0.02) << col << " amplitude " << s->amplitude;
    EXPECT_LT(rel_err(s->frequency, r.frequency), 0.01) << col << " frequency " << s->frequency;
  }
}

}  // namespace
