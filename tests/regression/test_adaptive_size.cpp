// The adaptive particle size (src/fluid/size_field.hpp) on the dam break's adaptive twin
// (cases/dam_break_tank/case_adaptive.json) through the wall impact: the graded column starts with fewer particles
// than the uniform one at the same finest size, the management merges and inserts particles as the flow moves
// while the water is kept, the particles' sizes reach the .vtu, and a run stopped and restarted from its checkpoint
// gives the whole run's probes bit for bit. Under the alpha detection (the fractional step's default) the twin also
// coarsens its column's core and keeps its water through the impact (the surface correction holds the area).
#include "case_runner.hpp"
#include "fluid_checks.hpp"
#include "process.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

using namespace lagfsi::testing;

const std::string kTwin = "cases/dam_break_tank/case_adaptive.json";

TEST(AdaptiveSize, TheDamBreakTwinFollowsItsSizeFieldAndKeepsItsWater) {
  const RunResult graded = run_case_1thread(kTwin, "adaptive_size_twin", {"analysis.end_time=0.4"});
  ASSERT_EQ(graded.exit_code, 0) << graded.stderr_text;
  const RunResult uniform =
      run_case_1thread("cases/dam_break_tank/case.json", "adaptive_size_uniform", {"analysis.end_time=0.01"});
  ASSERT_EQ(uniform.exit_code, 0) << uniform.stderr_text;
  const double n_graded = read_csv(graded.out_dir / "log.csv")["nodes"].front();
  const double n_uniform = read_csv(uniform.out_dir / "log.csv")["nodes"].front();
  EXPECT_LT(n_graded, 0.7 * n_uniform);
  const auto body = summary_of(graded)["bodies"][0];
  EXPECT_GT(body["remeshing"]["particles_coarsened"].get<long>(), 0);
  EXPECT_GT(body["remeshing"]["particles_inserted"].get<long>(), 0);
  EXPECT_LT(body["fluid_area"]["water_drift_max"].get<double>(), 0.005);
  // The sizes in the ParaView files: from h at the surface to several h inside the column.
  EXPECT_NE(file_text(graded.out_dir / "water" / "water_00000.vtu").find("particle_size"), std::string::npos);
}

TEST(AdaptiveSize, TheTwinFollowsItsSizeFieldUnderTheAlphaDetection) {
  const RunResult graded =
      run_case_1thread(kTwin, "adaptive_size_alpha",
                       {"analysis.end_time=0.4", "bodies.0.scheme.type=fractional_step", "bodies.0.preset=classic"});
  ASSERT_EQ(graded.exit_code, 0) << graded.stderr_text;
  const auto body = summary_of(graded)["bodies"][0];
  EXPECT_EQ(body["remeshing"]["domain_detection"], "alpha");
  EXPECT_GT(body["remeshing"]["particles_coarsened"].get<long>(), 0);
  const auto& area = body["fluid_area"];
  EXPECT_NEAR(area["final"].get<double>(), area["initial"].get<double>(), 0.002 * area["initial"].get<double>());
}

TEST(AdaptiveSize, AGradedRunRestartsBitForBit) {
  const std::vector<std::string> sets = {"analysis.end_time=0.35", "output.checkpoint.every_steps=20"};
  const RunResult full = run_case_1thread(kTwin, "adaptive_size_full", sets);
  ASSERT_EQ(full.exit_code, 0) << full.stderr_text;
  const fs::path dir = fresh_dir("adaptive_size_part");
  std::string args = "run \"" + (fs::path(LAGFSI_SOURCE_DIR) / kTwin).string() + "\" -o \"" + (dir / "out").string() +
                     "\" --quiet --threads 1";
  for (const auto& s : sets) args += " --set '" + s + "'";
  const RunResult part = run_lagfsi(args + " --stop-after-step 270", dir);
  ASSERT_EQ(part.exit_code, 0) << part.stderr_text;
  const RunResult rest = run_lagfsi(args + " --restart \"" + (dir / "out").string() + "\"", dir);
  ASSERT_EQ(rest.exit_code, 0) << rest.stderr_text;
  EXPECT_EQ(file_text(dir / "out" / "probes.csv"), file_text(full.out_dir / "probes.csv"));
  RunResult r = rest;
  r.out_dir = dir / "out";
  EXPECT_EQ(summary_of(r)["bodies"][0]["remeshing"]["particles_coarsened"],
            summary_of(full)["bodies"][0]["remeshing"]["particles_coarsened"]);
}

}  // namespace
