// Bad input never crashes, model by model: the MPM and shell inputs that must end with exit code != 0 and a
// one-line message naming the file, the JSON path and the reason (split from test_bad_input.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "bad_input.hpp"
#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;
using namespace lagfsi::testing::bad_input;
using nlohmann::json;

TEST(BadInput, MpmErrors) {
  const json base = json::parse(R"({
    "name": "bad_input_mpm",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.05},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "block", "type": "mpm",
      "material": {"type": "linear_elastic", "young": 1e6, "poisson": 0.3, "density": 1000},
      "grid": {"origin": [0, 0], "size": [1.0, 1.0], "cell": 0.1},
      "regions": [{"type": "rectangle", "origin": [0.2, 0.0], "size": [0.4, 0.4]}],
      "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [1, 0]}}]
    }]
  })");
  EXPECT_EQ(run_json("mpm_base", base).code, 0);
  json j = base;
  j["bodies"][0]["regions"][0]["origin"] = {5.0, 5.0};
  Outcome o = run_json("mpm_region_outside", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/regions/0", "outside the grid");
  j = base;
  j["bodies"][0]["grid"]["cell"] = 0.3;
  o = run_json("mpm_cell", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/grid/cell", "whole number");
  // A grid of 2.4e7 cells took 4.2 GB in check and 5.9 GB in a run (fuzzing round 4): at most 1e7 cells.
  j = base;
  j["bodies"][0]["grid"]["size"] = {1.0, 1.0e6};
  o = run_json("mpm_grid_too_large", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/grid", "more than 1e7");
  // A height probe outside the grid saw no particle and wrote nan at every step with exit 0.
  j = base;
  j["probes"] = json::parse(R"([{"name": "h", "type": "height", "body": "block", "x": 0.5}])");
  EXPECT_EQ(run_json("mpm_height_inside", j).code, 0);
  j["probes"][0]["x"] = 2500.0;
  o = run_json("mpm_height_outside", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/probes/0/x", "outside the grid");
  j = base;
  j["bodies"][0]["absorbing_boundaries"] =
      json::array({{{"select", {{"type", "segment"}, {"from", {0, 0}}, {"to", {1, 0}}}},
                    {"normal", {0, -1}},
                    {"free_field", true}}});
  o = run_json("mpm_free_field_base", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/absorbing_boundaries/0/normal", "lateral");
  j["bodies"][0]["absorbing_boundaries"][0] = {
      {"select", {{"type", "segment"}, {"from", {1, 0}}, {"to", {1, 1}}}}, {"normal", {1, 0}}, {"start", 5.0}};
  o = run_json("mpm_start_without_free_field", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/absorbing_boundaries/0/start", "free-field");
  j["bodies"][0]["absorbing_boundaries"][0]["free_field"] = true;
  j["bodies"][0]["absorbing_boundaries"][0]["start"] = 0.0;  // x = 1: no material next to it (the block ends at 0.6)
  o = run_json("mpm_free_field_empty", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/absorbing_boundaries/0/select", "no material");
  j = base;
  j["bodies"][0]["flip"] = 1.5;
  o = run_json("mpm_flip", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/flip", "[0, 1]");
  j = base;
  j["bodies"][0]["shape_functions"] = "bspline";
  o = run_json("mpm_shape", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/shape_functions", "gimp");
  j = base;
  j["bodies"][0]["material"] = {{"type", "mohr_coulomb"}, {"young", 1e6},           {"density", 1000},
                                {"cohesion", 0.0},        {"friction_angle", 30.0}, {"tension_cutoff", 10.0}};
  o = run_json("mpm_tension_cutoff", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/material/tension_cutoff", "c cot(phi)");
  j["bodies"][0]["material"].erase("tension_cutoff");
  j["bodies"][0]["time_integration"] = "implicit";  // with Mohr-Coulomb: not available
  o = run_json("mpm_implicit_plastic", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/time_integration", "linear elastic");
  // A block thrown out of its grid: the run stops with a solver error, the output so far stays valid.
  j = base;
  j["bodies"][0]["initial_velocity"] = {50.0, 0.0};
  o = run_json("mpm_leaves_grid", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "", "left the grid");
  EXPECT_TRUE(fs::exists(o.dir / "out" / "block.pvd"));
  std::ifstream summary(o.dir / "out" / "summary.json");
  EXPECT_EQ(json::parse(summary)["status"], "failed");
}

TEST(BadInput, MpmBodyTooStiffForTheExplicitStep) {
  // E = 1e14 on a 0.1 m grid: billions of stable substeps, a run that looked hung.
  const json j = json::parse(R"({
    "name": "bad_input_mpm_stiff",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 10},
    "bodies": [{
      "name": "block", "type": "mpm",
      "material": {"type": "linear_elastic", "young": 1e14, "poisson": 0.3, "density": 1},
      "grid": {"origin": [0, 0], "size": [1.0, 1.0], "cell": 0.1},
      "regions": [{"type": "rectangle", "origin": [0.2, 0.0], "size": [0.4, 0.4]}]
    }]
  })");
  const Outcome o = run_json("mpm_stiff", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/material", "substeps over the run");
}

TEST(BadInput, ShellErrorsNameTheirKey) {
  const json base = json::parse(R"({
    "name": "bad_input_shell",
    "analysis": {"type": "static", "load_steps": 2},
    "bodies": [{
      "name": "strip", "type": "shell",
      "material": {"type": "svk", "young": 1e8, "density": 1000, "hypothesis": "plane_stress"},
      "thickness": 0.01,
      "geometry": {"type": "line", "from": [0, 0], "to": [1, 0]},
      "mesh": {"elements": 4, "order": 3},
      "boundary_conditions": [{"type": "fixed", "select": {"type": "point", "at": [0, 0]}}],
      "loads": [{"type": "pressure", "select": {"type": "segment", "from": [0, 0.005], "to": [1, 0.005]}, "value": 10.0}]
    }]
  })");
  EXPECT_EQ(run_json("shell_base", base).code, 0);
  json j = base;
  j["bodies"][0].erase("thickness");
  Outcome o = run_json("shell_no_thickness", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/thickness", "missing");
  j = base;
  j["bodies"][0]["mesh"]["size"] = 0.1;  // both "elements" and "size"
  o = run_json("shell_mesh_both", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/mesh", "either");
  j = base;
  j["bodies"][0]["geometry"] = {{"type", "line"}, {"from", {0, 0}}, {"to", {0, 0}}};
  o = run_json("shell_zero_length", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/geometry", "zero length");
  j = base;
  j["bodies"][0]["material"]["type"] = "neo_hookean";
  o = run_json("shell_law", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/material/type", "svk");
  j = base;
  j["bodies"][0]["loads"][0]["select"] = {{"type", "segment"}, {"from", {0, 0.5}}, {"to", {1, 0.5}}};
  o = run_json("shell_pressure_nowhere", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/loads/0/select", "");
  // "rotation" belongs to shells only; "pinned" too.
  json s = base;
  s["bodies"][0]["type"] = "solid";
  s["bodies"][0]["geometry"] = {{"type", "rectangle"}, {"origin", {0, 0}}, {"size", {1, 0.1}}};
  s["bodies"][0]["mesh"] = {{"size", 0.1}, {"order", 1}};
  s["bodies"][0]["thickness"] = 1.0;
  s["bodies"][0]["loads"] = json::array();
  s["bodies"][0]["boundary_conditions"][0]["rotation"] = "free";
  o = run_json("solid_rotation", s);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/boundary_conditions/0/rotation", "unknown");
}

}  // namespace
