// The output of a run: every write is checked, so that a full disk, a file-size
// limit or a folder in a file's place ends the run with exit code 5 and one line naming the file, never
// "completed"; an output folder is locked while a run writes into it; the output folder is never the case
// file's own folder.
#include <gtest/gtest.h>

#include <sys/file.h>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"
#include "process.hpp"
#include "strip_case.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

/// The shared strip (tests/support/strip_case.hpp): `steps` steps, linear elements, VTK output or not.
json strip_case(int steps, bool vtk) {
  return lagfsi::testing::strip_case("output_strip", steps, 1, {{"every", 1}, {"vtk", vtk}});
}

fs::path write_case(const fs::path& dir, const json& j) {
  write_text(dir / "case.json", j.dump(2));
  return dir / "case.json";
}

std::string status_of(const fs::path& out) {
  std::ifstream in(out / "summary.json");
  if (!in) return "(no summary.json)";
  try {
    return json::parse(in).value("status", "(none)");
  } catch (const std::exception&) {
    return "(unreadable summary.json)";
  }
}

/// One line, exit code 5, naming a file of the output folder; never "completed".
void expect_output_failure(const Finished& r, const fs::path& out, const std::string& file_part,
                           const std::string& reason_part) {
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(file_part), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(reason_part), std::string::npos) << r.err;
  EXPECT_NE(status_of(out), "completed");
}

TEST(BadInputOutput, FileSizeLimitIsAFullDisk) {
  // RLIMIT_FSIZE = 16 kB: log.csv (about 150 bytes a row) reaches it after about 100 of its 400 rows. Before,
  // the run ended with exit 0 and "completed" over a cut log.csv.
  for (const bool vtk : {false, true}) {
    const fs::path dir = fresh_dir(std::string("output_fsize_") + (vtk ? "1" : "0"));
    const fs::path c = write_case(dir, strip_case(400, vtk));
    const Finished r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir, 16 * 1024);
    expect_output_failure(r, dir / "out", "", "cannot write (");
    EXPECT_TRUE(r.err.find("File too large") != std::string::npos ||
                r.err.find("out of disk space") != std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("vtk"), std::string::npos) << "no VTK log: " << r.err;
    if (vtk) {
      // The series stays valid: its last entry is a file that exists.
      const std::string pvd = file_text(dir / "out" / "strip.pvd");
      EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
      const auto at = pvd.rfind("file=\"");
      ASSERT_NE(at, std::string::npos);
      const std::string last = pvd.substr(at + 6, pvd.find('"', at + 6) - at - 6);
      EXPECT_TRUE(fs::exists(dir / "out" / last)) << last;
    }
  }
}

TEST(BadInputOutput, DeviceFullAndFolderInAFilesPlace) {
  // log.csv a link to /dev/full (every write: ENOSPC), then a folder where log.csv should be.
  const fs::path dir = fresh_dir("output_dev_full");
  const fs::path c = write_case(dir, strip_case(5, false));
  fs::create_directories(dir / "out");
  fs::create_symlink("/dev/full", dir / "out" / "log.csv");
  Finished r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  expect_output_failure(r, dir / "out", "log.csv", "No space left on device");
  fs::remove(dir / "out" / "log.csv");
  fs::create_directories(dir / "out" / "log.csv");
  r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  expect_output_failure(r, dir / "out", "log.csv", "Is a directory");
  // A folder where the body's .pvd should be (VTK on).
  fs::remove_all(dir / "out");
  fs::create_directories(dir / "out" / "strip.pvd");
  const fs::path c2 = write_case(dir, strip_case(5, true));
  r = run_args({"run", c2.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  expect_output_failure(r, dir / "out", "strip.pvd", "");
  // check's stdout on a full device.
  r = run_args({"check", c.string()}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const Spawned s = spawn_lagfsi({"check", c.string()}, "/dev/full", dir / "stderr_check.txt");
  EXPECT_EQ(wait_exit(s), 5);
  const std::string err = file_text(dir / "stderr_check.txt");
  EXPECT_EQ(count_lines(err), 1) << err;
  EXPECT_NE(err.find("stdout: cannot write"), std::string::npos) << err;
}

TEST(BadInputOutput, LockedOutputFolder) {
  // Another run holds the folder's lock: a second run fails at once, in one line, and writes nothing.
  const fs::path dir = fresh_dir("output_locked");
  const fs::path c = write_case(dir, strip_case(5, false));
  fs::create_directories(dir / "out");
  const int fd = ::open((dir / "out" / ".lagfsi.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  ASSERT_EQ(::write(fd, "4242\n", 5), 5);
  Finished r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("in use by another lagfsi run (process 4242)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "log.csv"));
  EXPECT_FALSE(fs::exists(dir / "out" / "resolved_case.json"));
  ::close(fd);  // the first run ends: the folder is free again
  r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(status_of(dir / "out"), "completed");
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock")) << "the run removes its lock file when it ends";
}

TEST(BadInputOutput, LockFileOfADeadRunAndEveryExit) {
  // A lock file left by a run that was killed (it names a process that no longer exists, and nobody holds the
  // lock) does not block the next run, which removes it at its end.
  const fs::path dir = fresh_dir("output_stale_lock");
  const fs::path c = write_case(dir, strip_case(5, false));
  fs::create_directories(dir / "out");
  write_text(dir / "out" / ".lagfsi.lock", "999999999\n");
  Finished r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock"));
  // A failed run (bad input found after the lock: a --restart without a checkpoint), an output error
  // (summary.json is a folder) and a solver failure remove it too.
  r = run_args({"run", c.string(), "--restart", (dir / "out").string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock"));
  fs::remove(dir / "out" / "summary.json");
  fs::create_directories(dir / "out" / "summary.json");
  r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  EXPECT_NE(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock"));
  fs::remove_all(dir / "out" / "summary.json");
  r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet", "--set", "analysis.max_step_halvings=0",
                "--set", "analysis.newton.max_iterations=1"},
               dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / ".lagfsi.lock"));
}

TEST(BadInputOutput, OutputFolderIsNotTheCaseFilesFolder) {
  const fs::path dir = fresh_dir("output_own_folder");
  const fs::path c = write_case(dir, strip_case(3, false));
  Finished r = run_args({"run", c.string(), "-o", dir.string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("the case file's own folder"), std::string::npos) << r.err;
  // Running a run's resolved_case.json into its own folder ("-o ." beside it, or the same path spelled
  // differently) would write over it.
  r = run_args({"run", c.string(), "-o", (dir / "out").string(), "--quiet"}, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path resolved = dir / "out" / "resolved_case.json";
  const std::string before = file_text(resolved);
  r = run_args({"run", resolved.string(), "-o", (dir / "out" / "." / "").string(), "--quiet"}, dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("own folder"), std::string::npos) << r.err;
  EXPECT_EQ(file_text(resolved), before);
}

}  // namespace
