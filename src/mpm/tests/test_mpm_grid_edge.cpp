// The edges of an MPM body's grid are free: a body that starts on an edge or in a corner with no boundary
// condition falls under gravity as a free body (u_y = -g t^2 / 2), and a particle that leaves the grid stops the
// run with one line naming the grid's JSON path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

json block_at(double x0, double y0, const std::string& shape) {
  json j = json::parse(R"({
    "name": "mpm_grid_edge",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.05},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "block", "type": "mpm",
      "material": {"type": "linear_elastic", "young": 1e6, "poisson": 0.3, "density": 1000},
      "grid": {"origin": [0, 0], "size": [1.0, 1.0], "cell": 0.1},
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.4, 0.4]}]
    }],
    "probes": [{"name": "uy", "type": "particle", "body": "block", "at": [0, 0], "quantity": "displacement_y"}]
  })");
  j["bodies"][0]["regions"][0]["origin"] = {x0, y0};
  j["bodies"][0]["shape_functions"] = shape;
  j["probes"][0]["at"] = {x0 + 0.2, y0 + 0.2};
  return j;
}

TEST(MpmGridEdge, ABodyOnAnEdgeOrInACornerOfItsGridWithNoSupportsFallsFreely) {
  const double t = 0.05, free_fall = -0.5 * 9.81 * t * t;  // -12.3 mm
  for (const std::string shape : {"linear", "gimp"})
    for (const auto& [x0, y0] : {std::pair{0.2, 0.0}, std::pair{0.0, 0.0}, std::pair{0.6, 0.6}, std::pair{0.0, 0.3}}) {
      const std::string tag =
          "mpm_grid_edge_" + shape + "_" + std::to_string(int(10 * x0)) + std::to_string(int(10 * y0));
      const RunResult r = run_case_text(fresh_dir(tag), block_at(x0, y0, shape).dump(2));
      ASSERT_EQ(r.exit_code, 0) << tag << ": " << r.stderr_text;
      const Csv c = probes_of(r);
      const double uy = c.col.at("uy").back();
      EXPECT_NEAR(uy, free_fall, 0.05 * std::abs(free_fall)) << tag;
    }
}

TEST(MpmGridEdge, AParticleThatLeavesTheGridStopsTheRunNamingTheGridPath) {
  json j = block_at(0.2, 0.0, "linear");
  j["analysis"]["end_time"] = 0.2;
  const RunResult r = run_case_text(fresh_dir("mpm_grid_edge_leaves"), j.dump(2));
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json: /bodies/0/grid: body 'block': particle"), std::string::npos)
      << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("left the grid (x 0..1, y 0..1)"), std::string::npos) << r.stderr_text;
  EXPECT_EQ(summary_of(r).at("status"), "failed");
}

}  // namespace
