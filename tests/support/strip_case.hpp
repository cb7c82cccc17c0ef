#pragma once
// A small dynamic solid for tests of the run itself (progress, output, interrupts): a 1 m x 0.1 m cantilever
// strip under gravity, 1 ms steps, one tip probe. Shared by test_run_progress and test_bad_input_output.
#include <nlohmann/json.hpp>

#include <string>

namespace lagfsi::testing {

/// The strip case named `name`, `steps` steps of 1 ms, elements of `order` (1 or 2), with `output` as its
/// "output" object.
inline nlohmann::json strip_case(const std::string& name, long steps, int order, const nlohmann::json& output) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "analysis": {"type": "dynamic", "dt": 1e-3},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "strip", "type": "solid",
      "material": {"type": "svk", "young": 1e6, "poisson": 0.3, "density": 1000},
      "geometry": {"type": "rectangle", "origin": [0, 0], "size": [1.0, 0.1]},
      "mesh": {"type": "structured", "size": 0.05},
      "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0, 0.1]}}]
    }],
    "probes": [{"name": "tip", "type": "displacement", "body": "strip", "at": [1.0, 0.05], "component": "y"}]
  })");
  j["name"] = name;
  j["bodies"][0]["mesh"]["order"] = order;
  j["analysis"]["end_time"] = static_cast<double>(steps) * 1e-3;
  j["output"] = output;
  return j;
}

}  // namespace lagfsi::testing
