// Fluid particles that leave the domain box are removed (issue #3: "drop particles that leave the domain's
// bounding box"). A blob translating at 2 m/s without gravity over a 1 m floor: the box is the floor and the
// initial blob enlarged by 10 % of its larger side (x <= 1.1 m here), so the particles past it are gone; when
// none is left the run stops with a message and exit code 3, its output valid.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

std::string blob_case(double end_time) {
  return R"({
    "name": "leaving_blob",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": )" + std::to_string(end_time) + R"(},
    "gravity": [0.0, 0.0],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "regions": [{"type": "rectangle", "origin": [0, 0.02], "size": [0.1, 0.1]}],
      "walls": [{"points": [[0, 0], [1.0, 0]]}],
      "initial_velocity": [2.0, 0.0],
      "scheme": {"type": "fractional_step", "volume_correction": false}
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

}  // namespace
