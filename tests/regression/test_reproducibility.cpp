// Runs on more than one thread are reproducible: the same case on the same number of threads gives the same
// probes.csv (and output series) to the last bit, because every sum of a parallel loop is taken in an order
// fixed by the number of threads (src/core/include/lagfsi/parallel_sum.hpp), and so a two-thread run stopped and
// restarted ends as the uninterrupted one does. The dam break runs fine enough for the fluid's element loop to be
// parallel from the first step (it is above 2000 elements); unordered sums changed the last digits there within a few
// steps, and the flow soon carried them into the probes' printed digits.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "case_runner.hpp"
#include "process.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

/// The dam break in a tank (monolithic PSPG, remeshed every step) with 6 mm particles: about 2350 elements.
const std::vector<std::string> kDamBreak{"cases/dam_break_tank/case.json", "bodies.0.spacing=0.006",
                                         "analysis.end_time=0.03", "output.every=10"};

/// `lagfsi run` of case_sets[0] with the --set overrides case_sets[1..] and the extra options, on two threads.
Finished run_two_threads(const std::vector<std::string>& case_sets, const std::vector<std::string>& options,
                         const fs::path& dir) {
  std::vector<std::string> args{"run", (fs::path(LAGFSI_SOURCE_DIR) / case_sets[0]).string(), "--quiet", "--threads",
                                "2"};
  args.insert(args.end(), options.begin(), options.end());
  for (size_t k = 1; k < case_sets.size(); ++k) {
    args.push_back("--set");
    args.push_back(case_sets[k]);
  }
  return run_args(args, dir);
}

json summary_in(const fs::path& out) { return json::parse(file_text(out / "summary.json")); }

/// The run used two threads and its fluid mesh was above the size at which the element loop runs in parallel.
void expect_parallel_fluid(const fs::path& out) {
  const json s = summary_in(out);
  EXPECT_EQ(s["threads"], 2);
  EXPECT_GE(s["bodies"][0]["elements"].get<long>(), 2000) << "the fluid's element loop would run serially";
}

TEST(Reproducibility, TwoThreadRunsOfADamBreakAreIdentical) {
  const fs::path dir = fresh_dir("reproducibility_dam_break");
  for (const char* run : {"a", "b"}) {
    const Finished r = run_two_threads(kDamBreak, {"-o", (dir / run).string()}, dir);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  expect_parallel_fluid(dir / "a");
  const std::string probes = file_text(dir / "a" / "probes.csv");
  EXPECT_GT(count_lines(probes), 30);
  EXPECT_EQ(file_text(dir / "b" / "probes.csv"), probes) << "two runs on two threads differ";
  // The last output of the series carries every particle's position, velocity and pressure to the last bit.
  for (const char* vtu : {"water/water_00003.vtu", "water/water_00001.vtu"})
    EXPECT_EQ(file_text(dir / "b" / vtu), file_text(dir / "a" / vtu)) << vtu;
}

TEST(Reproducibility, TwoThreadRestartOfADamBreakIsBitForBit) {
  // Stopped after 17 of the 30 steps (checkpoints every 5) and restarted, on two threads both times.
  const fs::path dir = fresh_dir("reproducibility_restart");
  std::vector<std::string> sets = kDamBreak;
  sets.push_back("output.checkpoint.every_steps=5");
  Finished r = run_two_threads(sets, {"-o", (dir / "full").string()}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_two_threads(sets, {"-o", (dir / "part").string(), "--stop-after-step", "17"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(summary_in(dir / "part")["status"], "stopped");
  r = run_two_threads(sets, {"--restart", (dir / "part").string()}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json s = summary_in(dir / "part");
  EXPECT_EQ(s["status"], "completed");
  EXPECT_EQ(s["restarted_from_step"], 17);
  expect_parallel_fluid(dir / "part");
  EXPECT_EQ(file_text(dir / "part" / "probes.csv"), file_text(dir / "full" / "probes.csv"))
      << "the restarted run's probes.csv differs from the uninterrupted one's";
  EXPECT_EQ(file_text(dir / "part" / "water/water_00003.vtu"), file_text(dir / "full" / "water/water_00003.vtu"));
}

TEST(Reproducibility, TwoThreadRunsOfAnMpmBodyAreIdentical) {
  // The granular column collapse (Mohr-Coulomb, explicit sub-steps) with 2 mm cells: 20 000 particles, the size
  // from which the particle-grid transfers run in parallel (per-thread grid copies summed in thread order).
  const std::vector<std::string> mpm{"cases/mpm_granular_collapse/case.json", "bodies.0.grid.cell=0.002",
                                     "analysis.end_time=0.005", "output.every=1"};
  const fs::path dir = fresh_dir("reproducibility_mpm");
  for (const char* run : {"a", "b"}) {
    const Finished r = run_two_threads(mpm, {"-o", (dir / run).string()}, dir);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const std::string probes = file_text(dir / "a" / "probes.csv");
  EXPECT_GE(count_lines(probes), 3);  // the header, t = 0 and the step
  EXPECT_EQ(file_text(dir / "b" / "probes.csv"), probes) << "two runs on two threads differ";
  EXPECT_EQ(file_text(dir / "b" / "bars_particles.csv"), file_text(dir / "a" / "bars_particles.csv"));
}

}  // namespace
