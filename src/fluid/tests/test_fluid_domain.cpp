// Fluid particles that leave the domain box are removed ("drop particles that leave the domain's
// bounding box"). A blob translating at 2 m/s without gravity over a 1 m floor: the box is the floor and the
// initial blob enlarged by 10 % of its larger side (x <= 1.1 m here), so the particles past it are gone; when
// none is left the run stops with a message and exit code 3, its output valid. With gravity the box is open
// upwards (a splash thrown above the walls falls back), and a drop whose step crosses a wall is put back on
// its side of the wall.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

std::string blob_case(double end_time) {
  return R"({
    "name": "leaving_blob",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": )" +
         std::to_string(end_time) + R"(},
    "gravity": [0.0, 0.0],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0, 0.02], "size": [0.1, 0.1]}],
      "walls": [{"points": [[0, 0], [1.0, 0]]}],
      "initial_velocity": [2.0, 0.0],
      "scheme": {"type": "fractional_step", "volume_correction": "none"}
    }],
    "probes": [{"name": "front", "type": "front", "body": "water", "floor": 0.02, "band": 0.2}],
    "output": {"every": 10}
  })";
}

RunResult run_blob(const std::string& tag, double end_time) {
  return run_case_text(fresh_dir(tag), blob_case(end_time));
}

TEST(FluidDomain, ParticlesPastTheBoxAreRemoved) {
  // At 0.52 s the blob spans x = 1.04-1.14: the particles beyond 1.1 are gone, the others go on.
  const RunResult r = run_blob("fluid_domain_partial", 0.52);
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv log = read_csv(r.out_dir / "log.csv");
  EXPECT_LT(log["nodes"].back(), log["nodes"].front());
  const Csv p = read_csv(r.out_dir / "probes.csv");
  // Particles are removed when the next step starts: after a step they may be one step's motion (4 mm) out.
  EXPECT_LE(p["front"].back(), 1.1 + 2.0 * 2e-3) << "no fluid beyond the box";
  EXPECT_GT(p["front"].back(), 1.05);
}

TEST(FluidDomain, AllFluidGoneStopsWithAMessage) {
  const RunResult r = run_blob("fluid_domain_all", 0.8);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.stderr_text.find("left the domain box"), std::string::npos) << r.stderr_text;
  std::ifstream pvd(r.out_dir / "water.pvd");
  std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos) << "the series written so far stays valid";
}

TEST(FluidDomain, ASplashThrownAboveTheWallsFallsBack) {
  // A blob in a 0.3 m tank thrown upwards at 3 m/s: its top rises to about 0.64 m, far above the box's top
  // (0.3 m walls + 10 %), and falls back into the tank (0.55 s, before it lands). None of it may be dropped.
  const RunResult r = run_case_text(fresh_dir("fluid_domain_splash"), R"({
    "name": "splash",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": 0.55},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0.1, 0.12], "size": [0.1, 0.06]}],
      "walls": [{"points": [[0, 0.3], [0, 0], [0.3, 0], [0.3, 0.3]]}],
      "initial_velocity": [0.0, 3.0],
      "scheme": {"type": "fractional_step", "volume_correction": "none"}
    }],
    "probes": [{"name": "top", "type": "column_height", "body": "water", "wall": 0.15, "band": 0.2}],
    "output": {"every": 50}
  })");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const Csv p = read_csv(r.out_dir / "probes.csv");
  double top = 0;
  for (double y : p["top"]) top = std::max(top, y);
  EXPECT_GT(top, 0.5) << "the blob rose above the box";
  const auto s = summary_of(r);
  EXPECT_EQ(s["bodies"][0]["fluid_area"]["left_domain"].get<double>(), 0.0);
}

std::string drop_at_wall_case(const std::string& inverted) {
  return R"({
    "name": "drop_at_wall",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.08},
    "gravity": [0.0, 0.0],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0.1, 0.0], "size": [0.04, 0.04]}],
      "walls": [{"points": [[0.5, -0.5], [0.5, 0.5]]}],
      "initial_velocity": [10.0, 0.0],
      "scheme": {"type": "fractional_step", "volume_correction": "none", "inverted_elements": ")" +
         inverted + R"("}
    }],
    "probes": [{"name": "reach", "type": "front", "body": "water", "floor": -0.5, "band": 1.0}],
    "output": {"every": 10}
  })";
}

TEST(FluidDomain, ADropDoesNotPassThroughAWall) {
  // A small blob flying at 10 m/s (half a spacing per step) against a wall at x = 0.5 m, no gravity: its
  // particles that end a step beyond the wall's line by more than 0.5 h (h for those in an element with a
  // wall particle) are put back on the near side. The impact turns elements over within a step: retried
  // with dt/2 by default, kept and left to the next remesh with "inverted_elements": "remesh".
  for (const std::string inverted : {"retry", "remesh"}) {
    const RunResult r = run_case_text(fresh_dir("fluid_domain_wall_" + inverted), drop_at_wall_case(inverted));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const Csv p = read_csv(r.out_dir / "probes.csv");
    for (size_t i = 0; i < p.rows(); ++i) EXPECT_LE(p["reach"][i], 0.5 + 0.02) << inverted << ", t " << p["time"][i];
    const auto s = summary_of(r);
    EXPECT_GT(s["bodies"][0]["wall_crossings"].get<long>(), 0) << inverted;
    EXPECT_EQ(s["bodies"][0]["fluid_area"]["left_domain"].get<double>(), 0.0) << inverted;
    if (inverted == "retry") {
      EXPECT_GT(s["step_retries"].get<long>(), 0);
      EXPECT_EQ(s["bodies"][0]["inverted_elements_kept"].get<long>(), 0);
    } else {
      EXPECT_EQ(s["step_retries"].get<long>(), 0);
      EXPECT_GT(s["bodies"][0]["inverted_elements_kept"].get<long>(), 0);
    }
  }
}

}  // namespace
