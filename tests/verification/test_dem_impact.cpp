// Verification of the DEM body (src/dem): Hertz impacts of Chung & Ooi (2011) tests 1 and 2 (contact duration,
// peak force and peak overlap within 1 % of Hertz, cases/dem_hertz_impact) and the restitution coefficient
// recovered within 1 % at impact speeds 0.05, 0.5 and 5 m/s for the linear and the Hertz laws
// (cases/dem_restitution).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fluid_checks.hpp"

namespace {

using namespace lagfsi::testing;

struct Impact {
  double duration = 0, peak_force = 0, peak_overlap = 0;
};

/// Contact from t = 0 (the bodies start touching) until the overlap returns to 0 (linear interpolation).
Impact impact(const Csv& c, const std::vector<double>& overlap, const std::string& force) {
  Impact r;
  const auto& t = c["time"];
  for (size_t i = 1; i < c.rows(); ++i) {
    r.peak_force = std::max(r.peak_force, c[force][i]);
    r.peak_overlap = std::max(r.peak_overlap, overlap[i]);
    if (overlap[i - 1] > 0 && overlap[i] <= 0) {
      r.duration = t[i - 1] + (t[i] - t[i - 1]) * overlap[i - 1] / (overlap[i - 1] - overlap[i]);
      break;
    }
  }
  return r;
}

TEST(DemHertzImpact, DurationPeakForceAndOverlapWithinOnePercentOfHertz) {
  const auto r = run_case_1thread("cases/dem_hertz_impact/case.json", "dem_hertz_impact");
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 100u);
  const Csv ref = read_csv(std::string(LAGFSI_SOURCE_DIR) +
                           "/cases/dem_hertz_impact/reference/dem_hertz_impact_chung_ooi_analytic.csv");
  auto row = [&](const std::string& material) {
    for (size_t i = 0; i < ref.rows(); ++i)
      if (ref.text.at("material")[i] == material) return i;
    ADD_FAILURE() << "no reference row " << material;
    return size_t(0);
  };
  std::vector<double> pair(c.rows()), wall(c.rows());
  for (size_t i = 0; i < c.rows(); ++i) {
    pair[i] = 0.02 - (c["pair_x1"][i] - c["pair_x0"][i]);
    wall[i] = 0.1 - c["wall_y"][i];
  }
  const struct {
    const char* name;
    Impact got;
    size_t ref;
  } tests[] = {{"test 1 glass pair", impact(c, pair, "pair_force"), row("glass")},
               {"test 2 Al wall", impact(c, wall, "wall_force"), row("Al_alloy")}};
  for (const auto& x : tests) {
    const double tc = ref["t_c_s"][x.ref], fm = ref["F_max_N"][x.ref], dm = ref["delta_max_m"][x.ref];
    std::printf("%s: t_c %.6g (Hertz %.6g, %+.3f %%), F_max %.6g (%.6g, %+.3f %%), delta_max %.6g (%.6g, %+.3f %%)\n",
                x.name, x.got.duration, tc, 100 * (x.got.duration / tc - 1), x.got.peak_force, fm,
                100 * (x.got.peak_force / fm - 1), x.got.peak_overlap, dm, 100 * (x.got.peak_overlap / dm - 1));
    EXPECT_LT(std::abs(x.got.duration / tc - 1), 0.01) << x.name;
    EXPECT_LT(std::abs(x.got.peak_force / fm - 1), 0.01) << x.name;
    EXPECT_LT(std::abs(x.got.peak_overlap / dm - 1), 0.01) << x.name;
  }
  // elastic: the rebound speeds equal the impact speeds, and the energy balance closes
  EXPECT_NEAR(c["pair_v0"].back(), -10.0, 0.01 * 10.0);
  EXPECT_NEAR(c["wall_vy"].back(), 0.2, 0.01 * 0.2);
  for (double b : c["wall_energy_balance"]) EXPECT_LT(std::abs(b), 1e-3 * 0.5 * 11.3 * 0.04);
}

void expect_restitution(double e, const std::string& tag) {
  const auto r = run_case_1thread(
      "cases/dem_restitution/case.json", tag,
      {"bodies.0.contact.restitution=" + std::to_string(e), "bodies.1.contact.restitution=" + std::to_string(e)});
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 10u);
  const std::vector<std::pair<std::string, double>> runs = {{"v005", 0.05}, {"v05", 0.5}, {"v5", 5.0}};
  for (const std::string law : {"linear", "hertz"})
    for (const auto& [col, v] : runs) {
      const double got = c[law + "_" + col].back() / v;
      std::printf("%s e = %.3f, impact %.2f m/s: restitution %.5f (%+.3f %%)\n", law.c_str(), e, v, got,
                  100 * (got / e - 1));
      EXPECT_LT(std::abs(got / e - 1), 0.01) << law << " at " << v << " m/s";
    }
  // the dissipated energy accounts for the lost kinetic energy (within 1 %)
  const double m = M_PI * 2500 * 0.005 * 0.005;
  const double lost = 0.5 * m * (0.05 * 0.05 + 0.25 + 25) * (1 - e * e);
  for (const std::string law : {"linear", "hertz"}) {
    EXPECT_NEAR(c[law + "_dissipated"].back(), lost, 0.01 * lost) << law;
    EXPECT_LT(std::abs(c[law + "_balance"].back()), 0.01 * lost) << law;
  }
}

TEST(DemRestitution, RecoveredWithinOnePercentOverSpeedsSpanning100x) {
  expect_restitution(0.5, "dem_restitution_05");
  expect_restitution(0.9, "dem_restitution_09");
}

}  // namespace
