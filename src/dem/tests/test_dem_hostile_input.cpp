// Hostile DEM input: every loop over a user's count has a bound a user can see, the wrong analysis is refused,
// an unsafe setting chosen on purpose is a warning (stderr and summary.json) and the instability it causes
// stops the run, messages name the real cause, and `lagfsi check` prints an error alone.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <lagfsi/dem/dem_particles.hpp>

#include <algorithm>
#include <chrono>

#include "case_runner.hpp"
#include "dem_base_case.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

json base_case() { return dem_base_case("dem_hostile_base"); }

/// A run (stderr with warnings unless quiet) in a fresh folder.
RunResult run(const std::string& tag, const json& j, const std::string& options = "--quiet") {
  return run_case_text(fresh_dir("dem_hostile_" + tag), j.dump(2), options);
}

size_t lines(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

void expect_one_line(const RunResult& r, const std::string& path, const std::string& reason) {
  EXPECT_NE(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_EQ(r.stderr_text.rfind("lagfsi: error: ", 0), 0u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(path), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(reason), std::string::npos) << r.stderr_text;
}

bool has_warning(const RunResult& r, const std::string& part) {
  const json s = summary_of(r);
  for (const auto& w : s.at("warnings"))
    if (w.get<std::string>().find(part) != std::string::npos) return true;
  return false;
}

TEST(DemHostileInput, AStaticAnalysisIsRefused) {
  json j = base_case();
  j["analysis"] = {{"type", "static"}, {"load_steps", 2}};
  expect_one_line(run("static", j), "/bodies/0/type", "dynamic analysis");
}

TEST(DemHostileInput, TooManyAttemptsOfARandomPackAreRefused) {
  json j = base_case();
  j["bodies"][0]["discs"][0] = json::parse(R"({"type": "random", "region": {"type": "rectangle",
      "origin": [0, 0], "size": [0.1, 0.05]}, "radius": 0.002, "fraction": 0.5, "attempts": 2000000000})");
  expect_one_line(run("attempts", j), "/bodies/0/discs/0/attempts", "at most 1000000");
}

TEST(DemHostileInput, ARandomPackStopsAtItsBudgetOfTrials) {
  // An unreachable fraction (equal discs jam near 0.547) with no limit on failures in a row: the budget ends it.
  const std::vector<lagfsi::Vec2> box = {{0.0, 0.0}, {0.05, 0.0}, {0.05, 0.05}, {0.0, 0.05}};
  lagfsi::dem::PackReport rep;
  const auto t0 = std::chrono::steady_clock::now();
  const auto discs = lagfsi::dem::random_pack(box, 0.002, 0.002, 0.6, 0, 1, 1 << 30, &rep, 200000);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(rep.trials, 200000);
  EXPECT_FALSE(rep.jammed);
  EXPECT_LT(rep.fraction, 0.6);
  EXPECT_FALSE(discs.empty());
  EXPECT_LT(seconds, 5.0);
}

TEST(DemHostileInput, ARandomPackThatJamsBelowItsFractionIsAWarningInTheSummary) {
  json j = base_case();
  j["bodies"][0]["discs"][0] = json::parse(R"({"type": "random", "region": {"type": "rectangle",
      "origin": [0, 0], "size": [0.1, 0.05]}, "radius": 0.002, "fraction": 0.59, "attempts": 500})");
  const RunResult r = run("jammed", j, "");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(has_warning(r, "/bodies/0/discs/0/fraction: the random pack jammed"));
  EXPECT_NE(r.stderr_text.find("lagfsi: warning: /bodies/0/discs/0/fraction"), std::string::npos) << r.stderr_text;
}

TEST(DemHostileInput, AStepAboveTheCriticalOneIsAWarningInTheSummary) {
  json j = base_case();
  j["bodies"][0]["time_step"] = {{"dt", 4e-3}, {"allow_above_critical", true}};
  j["analysis"]["dt"] = 4e-3;
  j["analysis"]["end_time"] = 4e-3;
  const RunResult r = run("above_critical", j, "");
  EXPECT_NE(r.stderr_text.find("lagfsi: warning: /bodies/0/time_step/dt: sub-steps of 0.004 s, above the critical"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_TRUE(has_warning(r, "/bodies/0/time_step/dt: sub-steps"));
  // Below the critical step (the driver's step cuts the sub-steps) nothing is unsafe: no warning.
  j["analysis"]["dt"] = 1e-5;
  j["analysis"]["end_time"] = 2e-5;
  const RunResult safe = run("above_critical_cut", j, "");
  EXPECT_EQ(safe.exit_code, 0) << safe.stderr_text;
  EXPECT_EQ(safe.stderr_text.find("warning"), std::string::npos) << safe.stderr_text;
}

TEST(DemHostileInput, AStepAboveTheCriticalOneThatBlowsUpStopsTheRunNamingTheStep) {
  json j = base_case();
  j["bodies"][0]["time_step"] = {{"dt", 3e-3}, {"allow_above_critical", true}};
  j["analysis"] = {{"type", "dynamic"}, {"dt", 3e-3}, {"end_time", 0.3}, {"max_step_halvings", 0}};
  const RunResult r = run("blow_up", j);
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("above the critical one"), std::string::npos) << r.stderr_text;
  const json s = summary_of(r);
  EXPECT_EQ(s.at("status"), "failed");
  EXPECT_LT(s.at("time").get<double>(), 0.3);
}

TEST(DemHostileInput, ADiscPushedThroughTheFloorStopsTheRun) {
  // 4 mm disc at 20 m/s onto a soft floor: the contact (k = 1e5 N/m, m = 0.13 kg) would let it pass through.
  json j = base_case();
  j["bodies"][0]["discs"] = json::parse(R"([{"type": "list", "discs": [[0.05, 0.01, 0.004]], "velocity": [0, -20]}])");
  j["analysis"]["end_time"] = 5e-3;
  const RunResult r = run("through_floor", j);
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("disc 0 crossed wall 'box' from"), std::string::npos) << r.stderr_text;
  // The same disc at 0.2 m/s bounces.
  j["bodies"][0]["discs"][0]["velocity"] = {0, -0.2};
  const RunResult slow = run("onto_floor", j);
  EXPECT_EQ(slow.exit_code, 0) << slow.stderr_text;
}

TEST(DemHostileInput, AnOverlapToleranceOfAWholeRadiusIsRefused) {
  json j = base_case();
  j["bodies"][0]["overlap_tolerance"] = 1.0;
  expect_one_line(run("tolerance", j), "/bodies/0/overlap_tolerance", "[0, 1)");
}

TEST(DemHostileInput, InitialOverlapsAcceptedByALargerToleranceAreAWarningInTheSummary) {
  json j = base_case();
  j["bodies"][0]["discs"] = json::parse(R"([{"type": "list", "discs": [[0.05, 0.0035, 0.004]]}])");
  j["bodies"][0]["overlap_tolerance"] = 0.2;
  const RunResult r = run("overlap_warning", j);
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(has_warning(r, "/bodies/0/overlap_tolerance: initial overlaps of up to 0.125 of the radius"));
  j["bodies"][0]["discs"][0]["discs"][0][1] = 0.004;  // touching: no warning
  const RunResult touching = run("overlap_touching", j);
  ASSERT_EQ(touching.exit_code, 0) << touching.stderr_text;
  EXPECT_TRUE(summary_of(touching).at("warnings").empty());
}

TEST(DemHostileInput, CoincidentDiscsAreNamedAsSuch) {
  json j = base_case();
  j["bodies"][0]["discs"] = json::parse(R"([{"type": "list", "discs": [[0.05, 0.01, 0.004], [0.05, 0.01, 0.003]]}])");
  j["bodies"][0]["overlap_tolerance"] = 0.4;
  expect_one_line(run("coincident", j), "/bodies/0/discs/0", "coincide");
}

TEST(DemHostileInput, AnOverflowIsBlamedOnItsCauseNotOnTheStep) {
  json j = base_case();
  j["bodies"][0]["contact"]["kn"] = 1e308;
  j["bodies"][0]["material"]["density"] = 1e-10;
  RunResult r = run("overflow", j);
  expect_one_line(r, "/bodies/0/contact", "not a finite positive number");
  EXPECT_EQ(r.stderr_text.find("steps"), std::string::npos) << r.stderr_text;
  j = base_case();
  j["bodies"][0]["material"]["density"] = 1e-310;  // m = rho pi r^2 underflows to 0
  r = run("underflow", j);
  expect_one_line(r, "/bodies/0/discs/0", "out of the range");
}

TEST(DemHostileInput, CoordinatesThatDoNotResolveTheRadiusAreRefused) {
  // A lattice at x = 1e300: x + pitch rounded back to x and the generator never advanced.
  json j = base_case();
  j["bodies"][0]["discs"][0]["region"]["origin"] = {1e300, 0};
  expect_one_line(run("far_lattice", j), "/bodies/0/discs/0/region", "do not resolve");
  j = base_case();
  j["bodies"][0]["walls"][0]["points"][0] = {1e300, 0.2};
  expect_one_line(run("far_wall", j), "/bodies/0/walls/0/points/0", "do not resolve");
}

TEST(DemHostileInput, NumbersOutOfRangeAreNamedAtTheirSource) {
  // A kinetic energy, a mass or a gravity that overflow the contacts' arithmetic: an input error naming the key,
  // not a run that ends with non-finite positions or an internal error.
  json j = base_case();
  j["bodies"][0]["discs"][0]["velocity"] = {1e300, 0};
  expect_one_line(run("fast", j), "/bodies/0/discs/0/velocity", "kinetic energy");
  j = base_case();
  j["bodies"][0]["material"]["density"] = 1e300;
  expect_one_line(run("heavy", j), "/bodies/0/discs/0", "1e-100 to 1e100 kg");
  j = base_case();
  j["gravity"] = {0, -1e300};
  expect_one_line(run("gravity", j), "/gravity", "smallest radius");
}

TEST(DemHostileInput, CheckPrintsAnErrorAlone) {
  // A valid DEM body before a bad probe: no line about the discs before the error.
  json j = base_case();
  j["probes"] = json::parse(R"([{"name": "e", "type": "energy", "body": "bed", "kind": "warmth"}])");
  const fs::path dir = fresh_dir("dem_hostile_check");
  write_text(dir / "case.json", j.dump(2));
  const RunResult c = run_lagfsi("check \"" + (dir / "case.json").string() + "\"", dir);
  expect_one_line(c, "/probes/0/kind", "warmth");
  const RunResult r = run("check_run", j, "");
  expect_one_line(r, "/probes/0/kind", "warmth");
}

}  // namespace
