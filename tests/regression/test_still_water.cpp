// Still water stays still under remeshing (issue #16, item 5): a tank at rest, remeshed every step for 20 s;
// the largest particle speed stays below 1e-4 sqrt(g H). Run with each domain detection: the alpha shape
// with its surface volume correction (the default) and the advected previous domain without correction, with
// wall particles and with the walls as constraints on the particles on them ("wall_model": "constraints"), and
// the latter with the Robin free-surface pressure ("free_surface_pressure": "robin"). A tank carried at constant
// velocity keeps its water, which moves with it (the domain box follows moving walls: before, a tank carried
// 0.5 m sideways lost 84 % of its water with the default settings and 93 % with the walls as constraints).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

std::string still_tank(const std::string& detection, const std::string& correction, const std::string& walls,
                       const std::string& free_surface_pressure) {
  return R"({
    "name": "still_water",
    "analysis": {"type": "dynamic", "dt": 0.01, "end_time": 20.0},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "domain_detection": ")" +
         detection + R"(", "wall_model": ")" + walls + R"(",
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.4, 0.2]}],
      "walls": [{"name": "tank", "points": [[0, 0.3], [0, 0], [0.4, 0], [0.4, 0.3]]}],
      "initial_pressure": {"type": "hydrostatic", "level": 0.2},
      "scheme": {"volume_correction": ")" +
         correction + R"(", "free_surface_pressure": ")" + free_surface_pressure + R"("}
    }],
    "probes": [{"name": "max_speed", "type": "max_speed", "body": "water"},
               {"name": "area", "type": "fluid_area", "body": "water"}],
    "output": {"every": 100000, "vtk": false}
  })";
}

void expect_still(const std::string& detection, const std::string& correction, const std::string& walls = "particles",
                  const std::string& free_surface_pressure = "dirichlet") {
  const RunResult r = run_case_text(fresh_dir("still_water_" + detection + "_" + walls + "_" + free_surface_pressure),
                                    still_tank(detection, correction, walls, free_surface_pressure));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv p = read_csv(r.out_dir / "probes.csv");
  const double limit = 1e-4 * std::sqrt(9.81 * 0.2);
  const auto& v = p["max_speed"];
  ASSERT_GT(v.size(), 1999u);
  EXPECT_LT(*std::max_element(v.begin(), v.end()), limit) << detection;
  const auto& a = p["area"];
  EXPECT_NEAR(a.back(), a.front(), 1e-6 * a.front()) << detection;
}

TEST(StillWater, AlphaShapeWithSurfaceCorrectionStaysStill) { expect_still("alpha", "surface"); }
TEST(StillWater, AdvectedDomainStaysStill) { expect_still("advected", "none"); }
TEST(StillWater, WallConstraintsStayStill) { expect_still("advected", "none", "constraints"); }
// The Robin free-surface pressure (fluid_element.hpp): the surface particles keep their continuity equation.
TEST(StillWater, RobinFreeSurfaceStaysStill) { expect_still("advected", "none", "constraints", "robin"); }

/// A tank 0.6 m wide carried at (0.5, 0.3) m/s for 1 s, its water moving with it from the start.
std::string carried_tank(const std::string& detection, const std::string& walls) {
  return R"({
    "name": "carried_tank",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": 1.0},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "domain_detection": ")" +
         detection + R"(", "wall_model": ")" + walls + R"(",
      "regions": [{"type": "rectangle", "origin": [0.1, 0], "size": [0.6, 0.2]}],
      "walls": [{"name": "tank", "points": [[0.1, 0.3], [0.1, 0], [0.7, 0], [0.7, 0.3]], "slip": true,
                 "motion": {"type": "prescribed_velocity", "value": [0.5, 0.3], "function": {"type": "constant"}}}],
      "initial_velocity": [0.5, 0.3],
      "initial_pressure": {"type": "hydrostatic", "level": 0.2}
    }],
    "probes": [{"name": "max_speed", "type": "max_speed", "body": "water"},
               {"name": "area", "type": "fluid_area", "body": "water"}],
    "output": {"vtk": false}
  })";
}

TEST(StillWater, ACarriedTankKeepsItsWater) {
  const double speed = std::hypot(0.5, 0.3);
  for (const auto& [detection, walls] : {std::pair<std::string, std::string>{"alpha", "particles"},
                                         std::pair<std::string, std::string>{"advected", "constraints"}}) {
    const RunResult r = run_case_text(fresh_dir("carried_tank_" + walls), carried_tank(detection, walls));
    ASSERT_EQ(r.exit_code, 0) << walls << ": " << r.stderr_text;
    const Csv p = read_csv(r.out_dir / "probes.csv");
    const auto& a = p["area"];
    const auto& v = p["max_speed"];
    EXPECT_EQ(summary_of(r)["bodies"][0]["fluid_area"]["left_domain"].get<double>(), 0.0) << walls;
    EXPECT_NEAR(a.back(), a.front(), 0.01 * a.front()) << walls;
    double dv = 0;
    for (double s : v) dv = std::max(dv, std::abs(s - speed));
    std::printf("tank carried at %.3f m/s, %s walls: area %.4f of the initial, largest speed off by %.1e m/s\n", speed,
                walls.c_str(), a.back() / a.front(), dv);
    // The walls as constraints hold it as a rigid body (measured 3e-11 m/s); the wall particles' layer
    // stirs it (a particle reached 2.3 m/s off).
    if (walls == "constraints") {
      EXPECT_LT(dv, 1e-6);
    }
  }
}

}  // namespace
