// A fluid boundary of the case file's "boundaries" (src/fluid/fluid_boundary.hpp), on the example type that
// prescribes the velocity of the fluid particles on a segment: a lid sliding over a layer of water at rest in a
// tank. The particles on the lid (not those the side walls already hold) move at the lid's velocity from the
// first step on, under either scheme, and a lid at rest leaves the water at rest.
#include "case_runner.hpp"
#include "process.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using namespace lagfsi::testing;

std::string lid_over_water(const std::string& scheme, double u) {
  return R"({
    "name": "lid",
    "analysis": {"type": "dynamic", "dt": 0.005, "end_time": 0.1},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1.0, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.4, 0.1]}],
      "walls": [{"name": "tank", "points": [[0, 0.3], [0, 0], [0.4, 0], [0.4, 0.3]]}],
      "boundaries": [{"type": "prescribed_velocity", "name": "lid", "segment": [[0, 0.1], [0.4, 0.1]],
                      "velocity": [)" +
         std::to_string(u) + R"(, 0.0]}],
      "initial_pressure": {"type": "hydrostatic", "level": 0.1},
      "scheme": {"type": ")" +
         scheme + R"("}
    }],
    "probes": [{"name": "max_speed", "type": "max_speed", "body": "water"}],
    "output": {"every": 100000, "vtk": false}
  })";
}

void expect_lid_drives(const std::string& scheme) {
  const double u = 0.05;
  const RunResult r = run_case_text(fresh_dir("lid_" + scheme), lid_over_water(scheme, u));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto s = summary_of(r);
  // 21 particles on the top row, the two at the corners held by the side walls.
  EXPECT_EQ(s["bodies"][0]["boundaries"]["lid"]["particles_held_max"].get<long>(), 19) << scheme;
  const Csv p = read_csv(r.out_dir / "probes.csv");
  ASSERT_EQ(p["max_speed"].size(), 21u);
  // The lid's particles move at its speed from the start; the water it drags is slower, but for the few
  // particles the lid pushes up the right-hand wall at the corner (the run-up of a lid on open water).
  for (double v : p["max_speed"]) {
    EXPECT_GE(v, u * (1 - 1e-9)) << scheme;
    EXPECT_LE(v, 1.5 * u) << scheme;
  }
}

TEST(FluidBoundaries, APrescribedVelocitySegmentMovesItsParticlesAtItsVelocityInTheMonolithicScheme) {
  expect_lid_drives("monolithic_pspg");
}

TEST(FluidBoundaries, APrescribedVelocitySegmentMovesItsParticlesAtItsVelocityInTheFractionalStep) {
  expect_lid_drives("fractional_step");
}

TEST(FluidBoundaries, ALidAtRestLeavesTheWaterAtRest) {
  const RunResult r = run_case_text(fresh_dir("lid_at_rest"), lid_over_water("monolithic_pspg", 0.0));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv p = read_csv(r.out_dir / "probes.csv");
  const auto& v = p["max_speed"];
  EXPECT_LT(*std::max_element(v.begin(), v.end()), 1e-4 * std::sqrt(9.81 * 0.1));
}

TEST(FluidBoundaries, ARunWithABoundaryRestartsBitForBit) {
  // The same run uninterrupted and stopped after step 7 (checkpoints every 5 steps), then restarted: the
  // boundary's step start and counters come back from the checkpoint.
  const auto [full, stopped, part] = run_and_restart(
      lid_over_water("monolithic_pspg", 0.05), "--quiet --threads 1 --set output.checkpoint.every_steps=5", 7, "lid");
  ASSERT_EQ(full.exit_code, 0) << full.stderr_text;
  ASSERT_EQ(stopped.exit_code, 0) << stopped.stderr_text;
  ASSERT_EQ(part.exit_code, 0) << part.stderr_text;
  EXPECT_EQ(file_text(part.out_dir / "probes.csv"), file_text(full.out_dir / "probes.csv"));
  EXPECT_EQ(summary_of(part)["bodies"][0]["boundaries"], summary_of(full)["bodies"][0]["boundaries"]);
}

TEST(FluidBoundaries, AnUnknownBoundaryTypeIsAnErrorListingTheTypes) {
  std::string text = lid_over_water("monolithic_pspg", 0.05);
  text.replace(text.find("prescribed_velocity"), std::string("prescribed_velocity").size(), "inflow_typo");
  const RunResult r = run_case_text(fresh_dir("lid_typo"), text);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("/bodies/0/boundaries/0/type"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("prescribed_velocity"), std::string::npos) << r.stderr_text;
}

}  // namespace
