// Bad DEM input never crashes: overlapping initial discs, a time step above the critical one, a charge inside the
// bed, unknown keys and bad laws end with a non-zero exit code and one line naming the file, the JSON path and the
// reason.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "case_runner.hpp"
#include "dem_base_case.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

json base_case() { return dem_base_case("dem_input_base"); }

struct Outcome {
  int code;
  std::string message;
};

Outcome run_json(const std::string& tag, const json& j) {
  const fs::path dir = fresh_dir("dem_input_" + tag);
  const RunResult r = run_case_text(dir, j.dump(2), "--quiet");
  return {r.exit_code, r.stderr_text};
}

void expect_error(const std::string& tag, const json& j, const std::string& path, const std::string& reason) {
  const Outcome o = run_json(tag, j);
  EXPECT_NE(o.code, 0) << tag;
  EXPECT_EQ(std::count(o.message.begin(), o.message.end(), '\n'), 1) << o.message;
  EXPECT_NE(o.message.find("case.json"), std::string::npos) << o.message;
  EXPECT_NE(o.message.find(path), std::string::npos) << o.message;
  EXPECT_NE(o.message.find(reason), std::string::npos) << o.message;
}

TEST(DemInput, TheBaseCaseRuns) { EXPECT_EQ(run_json("base", base_case()).code, 0); }

TEST(DemInput, OverlappingDiscs) {
  json j = base_case();
  j["bodies"][0]["discs"].push_back(json::parse(R"({"type": "list", "discs": [[0.002, 0.002, 0.002]]})"));
  expect_error("overlap", j, "/bodies/0/discs/1", "overlap");
}

TEST(DemInput, TimeStepAboveCritical) {
  json j = base_case();
  j["bodies"][0]["time_step"] = {{"dt", 1e-2}};
  expect_error("dt", j, "/bodies/0/time_step/dt", "critical");
  j["bodies"][0]["time_step"]["allow_above_critical"] = true;
  j["analysis"]["end_time"] = 2e-4;
  const Outcome o = run_json("dt_forced", j);  // forced: it runs (sub-steps no longer than the driver's 1e-4 s)
  EXPECT_EQ(o.code, 0) << o.message;
}

TEST(DemInput, ChargeInsideTheBed) {
  json j = base_case();
  j["bodies"][0]["blast"] = {{"charge_mass", 1.0}, {"position", {0.05, 0.02}}};
  expect_error("charge", j, "/bodies/0/blast/position", "inside the bed");
}

TEST(DemInput, BadLawAndKeys) {
  json j = base_case();
  j["bodies"][0]["contact"]["law"] = "hooke";
  expect_error("law", j, "/bodies/0/contact/law", "hooke");
  j = base_case();
  j["bodies"][0]["contact"]["kn"] = -1;
  expect_error("kn", j, "/bodies/0/contact/kn", "positive");
  j = base_case();
  j["bodies"][0]["contact"]["restitution_coefficient"] = 0.5;
  expect_error("key", j, "/bodies/0/contact/restitution_coefficient", "unknown key");
  j = base_case();
  j["bodies"][0]["walls"][0]["points"] = json::array({json::array({0, 0})});
  expect_error("wall", j, "/bodies/0/walls/0/points", "at least 2");
}

}  // namespace
