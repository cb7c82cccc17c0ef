// Hostile MPM input that the explicit sub-step cannot follow (an initial velocity or a gravity that carries a
// particle across a cell in one sub-step, an unstable mass-proportional damping, an initial stress above the
// P-wave modulus) is an input error naming its key, not a run that stops at t = 0 on an "inverted or
// non-finite" particle.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

json block() {
  return json::parse(R"({
    "name": "mpm_hostile",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 5e-3},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "block", "type": "mpm",
      "material": {"type": "linear_elastic", "young": 1e6, "poisson": 0.3, "density": 1000},
      "grid": {"origin": [0, 0], "size": [1.0, 1.0], "cell": 0.1},
      "regions": [{"type": "rectangle", "origin": [0.2, 0.0], "size": [0.4, 0.4]}],
      "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [1, 0]}}]
    }]
  })");
}

void expect_one_line(const std::string& tag, const json& j, const std::string& path, const std::string& reason) {
  const RunResult r = run_case_text(fresh_dir("mpm_hostile_" + tag), j.dump(2));
  EXPECT_EQ(r.exit_code, 2) << tag << ": " << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json: " + path + ": "), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(reason), std::string::npos) << r.stderr_text;
}

TEST(MpmHostileInput, TheBlockRuns) {
  EXPECT_EQ(run_case_text(fresh_dir("mpm_hostile_base"), block().dump(2)).exit_code, 0);
}

TEST(MpmHostileInput, AnInitialStateTheExplicitStepCannotFollowIsAnInputErrorNamingItsKey) {
  json j = block();
  j["bodies"][0]["initial_velocity"] = {1e300, 0};
  expect_one_line("velocity", j, "/bodies/0/initial_velocity", "cross more than a cell");
  j = block();
  j["bodies"][0]["initial_state"] = {{"type", "pulse"}, {"amplitude", 2e9}, {"centre", 0.4}, {"width", 0.1}};
  expect_one_line("pulse", j, "/bodies/0/initial_state", "cross more than a cell");
  j = block();
  j["gravity"] = {0, -2147483648.0};
  expect_one_line("gravity", j, "/gravity", "carries a particle across more than a cell");
  j = block();
  j["bodies"][0]["damping"] = {{"mass", 1e300}};
  expect_one_line("damping", j, "/bodies/0/damping/mass", "diverges");
  j = block();
  j["bodies"][0]["initial_stress"] = {{"type", "geostatic"}, {"surface", 1e300}};
  expect_one_line("stress", j, "/bodies/0/initial_stress", "P-wave modulus");
}

}  // namespace
