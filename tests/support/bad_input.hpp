#pragma once
// The bad-input tests' helpers (test_bad_input.cpp, test_bad_input_models.cpp): a small valid static case to
// mutate, running a case text into a fresh folder, and the one-line error check.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "case_runner.hpp"

namespace lagfsi::testing::bad_input {

using namespace lagfsi::testing;
using nlohmann::json;

/// A small valid static case (cantilever strip, T3), used as the base for each mutation.
inline json base_case() {
  return json::parse(R"({
    "name": "bad_input_base",
    "analysis": {"type": "static", "load_steps": 2},
    "bodies": [{
      "name": "strip", "type": "solid",
      "material": {"type": "svk", "young": 1e6, "poisson": 0.3, "density": 1000},
      "geometry": {"type": "rectangle", "origin": [0, 0], "size": [1.0, 0.1]},
      "mesh": {"type": "structured", "size": 0.05, "order": 1},
      "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0, 0.1]}}],
      "loads": [{"type": "point_load", "select": {"type": "point", "at": [1.0, 0.1]}, "value": [0, -1.0]}]
    }],
    "probes": [{"name": "tip", "type": "displacement", "body": "strip", "at": [1.0, 0.05]}]
  })");
}

struct Outcome {
  int code;
  std::string message;
  fs::path dir;
};

inline Outcome run_text(const std::string& tag, const std::string& text, const std::string& extra = "") {
  const fs::path dir = fresh_dir("bad_input_" + tag);
  const RunResult r = run_case_text(dir, text, "--quiet " + extra);
  return {r.exit_code, r.stderr_text, dir};
}

inline Outcome run_json(const std::string& tag, const json& j, const std::string& extra = "") {
  return run_text(tag, j.dump(2), extra);
}

/// One line, naming the file and (if given) the JSON path.
inline void expect_one_line(const Outcome& o, const std::string& path, const std::string& reason_part) {
  ASSERT_FALSE(o.message.empty());
  EXPECT_EQ(std::count(o.message.begin(), o.message.end(), '\n'), 1) << o.message;
  EXPECT_NE(o.message.find("case.json"), std::string::npos) << o.message;
  if (!path.empty()) {
    EXPECT_NE(o.message.find(path), std::string::npos) << o.message;
  }
  EXPECT_NE(o.message.find(reason_part), std::string::npos) << o.message;
}

}  // namespace lagfsi::testing::bad_input
