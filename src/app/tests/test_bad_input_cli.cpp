// The command line: --threads bounded by the machine; usage errors on one line;
// --help for every command, exit 0; echoed keys and values cut to about 80 characters.
#include <gtest/gtest.h>

#include <thread>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"
#include "process.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

const char* kCase = R"({
  "name": "cli_strip",
  "analysis": {"type": "static", "load_steps": 1},
  "bodies": [{
    "name": "strip", "type": "solid",
    "material": {"type": "svk", "young": 1e6, "poisson": 0.3, "density": 1000},
    "geometry": {"type": "rectangle", "origin": [0, 0], "size": [1.0, 0.1]},
    "mesh": {"type": "structured", "size": 0.1, "order": 1},
    "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0, 0.1]}}]
  }],
  "output": {"vtk": false}
})";

void expect_usage_line(const Finished& r, const std::string& part) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("lagfsi: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 300u) << r.err;
}

TEST(BadInputCli, ThreadsBoundedByTheMachine) {
  const fs::path dir = fresh_dir("cli_threads");
  write_text(dir / "case.json", kCase);
  const std::string c = (dir / "case.json").string(), o = (dir / "out").string();
  // 100 000 threads crashed the OpenMP runtime (SIGSEGV, no summary).
  expect_usage_line(run_args({"run", c, "-o", o, "--threads", "100000"}, dir), "at most");
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  expect_usage_line(run_args({"run", c, "-o", o, "--threads", std::to_string(4 * hw + 1)}, dir), "at most");
  expect_usage_line(run_args({"run", c, "-o", o, "--threads", "99999999999999999999"}, dir), "--threads");
  expect_usage_line(run_args({"run", c, "-o", o, "--threads", "0"}, dir), "positive integer");
  expect_usage_line(run_args({"run", c, "-o", o, "--threads", "-3"}, dir), "positive integer");
  EXPECT_EQ(run_args({"run", c, "-o", o, "--quiet", "--threads", std::to_string(4 * hw)}, dir).code, 0);
  EXPECT_EQ(run_args({"run", c, "-o", o, "--quiet", "--threads=1"}, dir).code, 0);
}

TEST(BadInputCli, UsageErrorsOnOneLine) {
  const fs::path dir = fresh_dir("cli_usage");
  write_text(dir / "case.json", kCase);
  const std::string c = (dir / "case.json").string();
  expect_usage_line(run_args({}, dir), "no command");
  expect_usage_line(run_args({"frobnicate"}, dir), "unknown command 'frobnicate'");
  expect_usage_line(run_args({"run"}, dir), "run needs a case file");
  expect_usage_line(run_args({"check"}, dir), "check needs a case file");
  expect_usage_line(run_args({"run", c, "--bogus"}, dir), "unknown option '--bogus'");
  expect_usage_line(run_args({"run", c, c}, dir), "unexpected argument");
  expect_usage_line(run_args({"run", c, "-o"}, dir), "-o needs a folder");
  expect_usage_line(run_args({"run", c, "--set"}, dir), "--set needs key.path=value");
  expect_usage_line(run_args({"run", c, "--progress", "fancy"}, dir), "--progress: unknown mode 'fancy'");
  expect_usage_line(run_args({"check", c, "-o", "x"}, dir), "an option of run");
}

TEST(BadInputCli, HelpForEveryCommand) {
  const fs::path dir = fresh_dir("cli_help");
  const std::vector<std::vector<std::string>> asks = {{"--help"},
                                                      {"-h"},
                                                      {"help"},
                                                      {"help", "run"},
                                                      {"help", "check"},
                                                      {"run", "--help"},
                                                      {"check", "--help"},
                                                      {"run", "-h"},
                                                      {"run", "case.json", "--threads", "x", "--help"},
                                                      {"check", "--set", "a=b", "--help"}};
  for (const auto& a : asks) {
    const Finished r = run_args(a, dir);
    EXPECT_EQ(r.code, 0) << a[0] << " " << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("usage: lagfsi"), std::string::npos) << r.out;
  }
  EXPECT_NE(run_args({"run", "--help"}, dir).out.find("--progress"), std::string::npos);
  EXPECT_NE(run_args({"check", "--help"}, dir).out.find("lagfsi check CASE.json"), std::string::npos);
}

TEST(BadInputCli, EchoedKeysAreCut) {
  const fs::path dir = fresh_dir("cli_echo");
  write_text(dir / "case.json", kCase);
  const std::string c = (dir / "case.json").string();
  const std::string key(100000, 'k');
  // A 100 000-character key was echoed whole: in --set, as an option, in the case file.
  Finished r = run_args({"check", c, "--set", key + "=1"}, dir);
  EXPECT_EQ(r.code, 2) << r.err.size();
  EXPECT_EQ(count_lines(r.err), 1);
  EXPECT_LT(r.err.size(), 400u);
  EXPECT_NE(r.err.find("(100000 bytes)"), std::string::npos) << r.err;
  r = run_args({"check", c, "--set", "analysis." + key + "=1"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_LT(r.err.size(), 600u);  // the valid keys are listed
  r = run_args({"check", c, "--" + key}, dir);
  expect_usage_line(r, "unknown option");
  r = run_args({"check", c, "--set", "analysis.type=" + key}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_LT(r.err.size(), 400u) << r.err.substr(0, 400);
  json j = json::parse(kCase);
  j["bodies"][0][key] = 1;
  write_text(dir / "long_key.json", j.dump());
  r = run_args({"check", (dir / "long_key.json").string()}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(count_lines(r.err), 1);
  EXPECT_LT(r.err.size(), 800u);
  EXPECT_NE(r.err.find("unknown key"), std::string::npos) << r.err.substr(0, 800);
}

}  // namespace
