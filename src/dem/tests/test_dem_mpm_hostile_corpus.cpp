// A corpus of hostile DEM and MPM case files (tests/fuzz/dem_mpm_corpus, listed with what each must do in its
// index.json): mutants of a small DEM and a small MPM case (numbers set to 0, negative, huge, tiny, "nan" or "inf"
// as strings, wrong types, keys removed or added, objects wrapped in arrays) that once crashed, hung or completed
// over a wrong answer, and the defect classes they stand for. Each is run by `lagfsi check` or a short run under a
// time limit: no signal, no hang, and a failure is one line naming the file and the JSON path or the cause.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

const fs::path kCorpus = fs::path(LAGFSI_SOURCE_DIR) / "tests" / "fuzz" / "dem_mpm_corpus";

struct Ran {
  int code;  // exit code; 124: the time limit; 1000 + signal
  std::string err;
  double seconds;
};

/// `timeout 30 lagfsi <command> <file>` (a run with its output in `dir`/out).
Ran run_under_limit(const std::string& command, const fs::path& file, const fs::path& dir) {
  std::string cmd = "timeout 30 \"" + std::string(LAGFSI_EXE) + "\" " + command + " \"" + file.string() + "\"";
  if (command == "run") cmd += " -o \"" + (dir / "out").string() + "\" --quiet";
  cmd += " > \"" + (dir / "stdout.txt").string() + "\" 2> \"" + (dir / "stderr.txt").string() + "\"";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream in(dir / "stderr.txt");
  std::stringstream ss;
  ss << in.rdbuf();
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  return {code, ss.str(), s};
}

TEST(DemMpmHostileCorpus, EveryFileEndsAsItsIndexSaysInOneLineAndInTime) {
  const json index = json::parse(std::ifstream(kCorpus / "index.json"));
  ASSERT_GE(index.size(), 20u);
  for (const auto& e : index) {
    const std::string file = e.at("file");
    const std::string command = e.at("command");
    const int expected = e.at("exit");
    const fs::path dir = fresh_dir("hostile_corpus_" + fs::path(file).stem().string());
    const Ran r = run_under_limit(command, kCorpus / file, dir);
    SCOPED_TRACE(file + " (" + command + "): " + r.err);
    EXPECT_EQ(r.code, expected);
    EXPECT_LT(r.seconds, 20.0);
    if (expected != 0) {
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
      EXPECT_EQ(r.err.rfind("lagfsi: error: " + (kCorpus / file).string() + ": ", 0), 0u);
      EXPECT_NE(r.err.find(e.at("message").get<std::string>()), std::string::npos);
    }
    if (command == "run" && fs::exists(dir / "out" / "summary.json")) {
      const json s = json::parse(std::ifstream(dir / "out" / "summary.json"));
      EXPECT_EQ(s.at("status"), expected == 0 ? "completed" : "failed");
      if (e.contains("warning")) {
        const std::string w = e.at("warning");
        const auto& ws = s.at("warnings");
        EXPECT_TRUE(std::any_of(ws.begin(), ws.end(),
                                [&](const json& x) { return x.get<std::string>().find(w) != std::string::npos; }));
      }
    }
  }
}

}  // namespace
