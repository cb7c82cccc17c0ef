// Watching and interrupting a run: progress on stderr as a status line redrawn in
// place (bar) or as a line at each tenth of the run (lines; also every 5 s of wall time), a table of where the
// time went at the end, nothing with --quiet; SIGINT and SIGTERM end the current step, write the output and
// summary.json ("interrupted") and exit with 128 + the signal's number.
#include <gtest/gtest.h>

#include <csignal>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"
#include "process.hpp"
#include "strip_case.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

/// The shared strip (tests/support/strip_case.hpp): `steps` steps of 1 ms, quadratic elements, VTK output.
json strip_case(long steps, int output_every) {
  return lagfsi::testing::strip_case("progress_strip", steps, 2, {{"every", output_every}, {"vtk", true}});
}

struct Outcome {
  Finished r;
  fs::path out;
  json summary;
};

Outcome run(const std::string& tag, const json& j, const std::vector<std::string>& extra) {
  const fs::path dir = fresh_dir("progress_" + tag);
  write_text(dir / "case.json", j.dump(2));
  std::vector<std::string> args{"run", (dir / "case.json").string(), "-o", (dir / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  Outcome x{run_args(args, dir), dir / "out", {}};
  std::ifstream in(x.out / "summary.json");
  if (in) x.summary = json::parse(in);
  return x;
}

long count_of(const std::string& s, const std::string& what) {
  long n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

void expect_time_table(const std::string& err) {
  EXPECT_NE(err.find("where the time went"), std::string::npos) << err;
  for (const char* phase : {"assembly", "factorization", "solve", "output", "other"})
    EXPECT_NE(err.find(std::string("  ") + phase), std::string::npos) << phase << "\n" << err;
}

TEST(RunProgress, LinesToAFile) {
  // 300 steps: one line per tenth (and one per 5 s of wall time), not one per step (1015 lines before).
  const Outcome x = run("lines", strip_case(300, 50), {"--progress", "lines"});
  ASSERT_EQ(x.r.code, 0) << x.r.err;
  const long status =
      count_of(x.r.err, "[progress_strip] ") - count_of(x.r.err, "where the time went") - count_of(x.r.err, "] done:");
  const double wall = x.summary["wall_time"].get<double>();
  EXPECT_GE(status, 10) << x.r.err;
  EXPECT_LE(status, 10 + 1 + static_cast<long>(wall / 5.0)) << x.r.err;
  for (const char* tenth : {" 10% step", " 50% step", "100% step 300 "})
    EXPECT_NE(x.r.err.find(tenth), std::string::npos) << tenth << "\n" << x.r.err;
  EXPECT_EQ(x.r.err.find('\r'), std::string::npos);
  expect_time_table(x.r.err);
  // "auto" to a file is lines too; log.csv keeps one row per step.
  const Outcome a = run("auto", strip_case(30, 50), {});
  ASSERT_EQ(a.r.code, 0) << a.r.err;
  EXPECT_EQ(a.r.err.find('\r'), std::string::npos);
  EXPECT_NE(a.r.err.find("100% step 30 "), std::string::npos) << a.r.err;
  EXPECT_EQ(read_csv(a.out / "log.csv").rows(), 30u);
}

TEST(RunProgress, BarQuietAndNone) {
  // The bar redraws one line in place ("\r", then "\033[K" clears the rest of it), ends with a newline.
  const Outcome b = run("bar", strip_case(100, 50), {"--progress", "bar"});
  ASSERT_EQ(b.r.code, 0) << b.r.err;
  EXPECT_GE(count_of(b.r.err, "\r"), 1);
  EXPECT_NE(b.r.err.find("#####] 100% step 100 "), std::string::npos) << b.r.err;  // a full bar at the end
  EXPECT_LE(count_lines(b.r.err), 12) << "a table, not a line per step";
  expect_time_table(b.r.err);
  // --quiet: nothing at all; --progress none: no status and no table (the final line stays).
  const Outcome q = run("quiet", strip_case(20, 50), {"--quiet"});
  ASSERT_EQ(q.r.code, 0) << q.r.err;
  EXPECT_TRUE(q.r.err.empty()) << q.r.err;
  const Outcome n = run("none", strip_case(20, 50), {"--progress", "none"});
  ASSERT_EQ(n.r.code, 0) << n.r.err;
  EXPECT_EQ(count_lines(n.r.err), 1) << n.r.err;
  EXPECT_NE(n.r.err.find("] done:"), std::string::npos) << n.r.err;
}

/// Starts a run that would take 100 000 steps, waits until log.csv has `rows` rows, sends `sig`.
Outcome interrupted(const std::string& tag, int sig) {
  const fs::path dir = fresh_dir("progress_" + tag);
  write_text(dir / "case.json", strip_case(100000, 7).dump(2));
  const fs::path out = dir / "out";
  const Spawned s = spawn_lagfsi({"run", (dir / "case.json").string(), "-o", out.string(), "--progress", "lines"},
                                 dir / "stdout.txt", dir / "stderr.txt");
  // Waiting for the run to be under way (not a timing assertion: only how long to wait at most).
  for (int i = 0; i < 6000; ++i) {
    if (fs::exists(out / "log.csv") && count_lines(file_text(out / "log.csv")) > 12) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(s.pid, sig);
  Outcome x{{wait_exit(s), file_text(dir / "stdout.txt"), file_text(dir / "stderr.txt")}, out, {}};
  std::ifstream in(out / "summary.json");
  if (in) x.summary = json::parse(in);
  return x;
}

void expect_interrupted(const Outcome& x, int sig, const std::string& name) {
  EXPECT_EQ(x.r.code, 128 + sig) << x.r.err;
  ASSERT_TRUE(x.summary.is_object());
  EXPECT_EQ(x.summary["status"], "interrupted");
  EXPECT_EQ(x.summary["signal"], name);
  const long steps = x.summary["steps"].get<long>();
  EXPECT_GT(steps, 10);
  EXPECT_LT(steps, x.summary["steps_planned"].get<long>());
  // The files agree with the summary: a row per step, a probe sample per step and the initial one.
  EXPECT_EQ(static_cast<long>(read_csv(x.out / "log.csv").rows()), steps);
  const Csv probes = read_csv(x.out / "probes.csv");
  EXPECT_EQ(static_cast<long>(probes.rows()), steps + 1);
  EXPECT_NEAR(probes["time"].back(), x.summary["time"].get<double>(), 1e-12);
  // The series is valid and ends with the last step's state (written although 7 does not divide the step).
  const std::string pvd = file_text(x.out / "strip.pvd");
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  const auto at = pvd.rfind("timestep=\"");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(pvd.substr(at + 10)), x.summary["time"].get<double>(), 1e-12);
  const auto f = pvd.rfind("file=\"");
  EXPECT_TRUE(fs::exists(x.out / pvd.substr(f + 6, pvd.find('"', f + 6) - f - 6)));
  // One line says so, after the time table.
  EXPECT_NE(x.r.err.find("lagfsi: interrupted by " + name + " after step " + std::to_string(steps)), std::string::npos)
      << x.r.err;
  EXPECT_FALSE(fs::exists(x.out / ".lagfsi.lock")) << "the run removes its lock file";
  expect_time_table(x.r.err);
}

TEST(RunProgress, InterruptEndsTheStepAndWritesTheOutput) {
  expect_interrupted(interrupted("sigint", SIGINT), SIGINT, "SIGINT");
  expect_interrupted(interrupted("sigterm", SIGTERM), SIGTERM, "SIGTERM");
}

}  // namespace
