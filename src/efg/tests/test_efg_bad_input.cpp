// Bad EFG input never crashes, hangs or completes over a wrong answer (the findings of a fuzzing round over the
// EFG case files, tests/fuzz/fuzz_cases.py): each ends with a non-zero exit and one line naming the case file and
// the JSON path of the input at fault. Input the set-up can judge is exit 2 (bad input); a load step that cannot
// be solved is exit 3 at the body's control, and the output written so far stays valid.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "bad_input.hpp"
#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;
using namespace lagfsi::testing::bad_input;
using nlohmann::json;

/// A small EFG cantilever (8 x 2 cells, bilinear basis, coupled clamped end, end shear): one load step.
json efg_case() {
  return json::parse(R"({
    "name": "efg_bad_input",
    "analysis": {"type": "static", "load_steps": 1, "newton": {"max_iterations": 5, "residual_tolerance": 1e-10}},
    "bodies": [{
      "name": "beam", "type": "efg",
      "domain": {"type": "rectangle", "origin": [0, 0], "size": [4.0, 1.0], "divisions": [8, 2]},
      "material": {"type": "linear_elastic", "young": 1000.0, "poisson": 0.3},
      "efg": {"basis": "bilinear", "alpha": 2.0, "gauss": 3},
      "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0, 1]}}],
      "loads": [{"type": "traction", "select": {"type": "segment", "from": [4, 0], "to": [4, 1]}, "value": [0, -1]}]
    }],
    "probes": [{"name": "tip", "type": "displacement", "body": "beam", "at": [4, 0], "component": "y"}]
  })");
}

/// A failed run leaves a summary.json that says so.
void expect_failed_summary(const Outcome& o) {
  const json s = json::parse(std::ifstream(o.dir / "out" / "summary.json"));
  EXPECT_EQ(s.at("status"), "failed");
}

TEST(EfgInput, TheBaseCaseRuns) { EXPECT_EQ(run_json("efg_base", efg_case()).code, 0); }

// A support shrunk to one point (a segment from (0, 0) to (0, 0)), or one whose far end overflows (1e300), held
// the body at one node: free to rotate, the stiffness singular, and the run ended in "Newton did not converge"
// with no path.
TEST(EfgInput, SupportsThatLeaveTheBodyFreeToMoveAreAnErrorNamingTheBoundaryConditions) {
  json j = efg_case();
  j["bodies"][0]["boundary_conditions"][0]["select"]["to"] = {0, 0};
  Outcome o = run_json("efg_support_point", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/boundary_conditions", "rigid rotation");
  j["bodies"][0]["boundary_conditions"][0]["select"]["to"] = {0, 1e300};
  o = run_json("efg_support_overflow", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/boundary_conditions", "free to move");
  j["bodies"][0]["boundary_conditions"][0]["components"] = "y";
  j["bodies"][0]["boundary_conditions"][0]["select"]["to"] = {0, 1};
  o = run_json("efg_support_y_only", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/boundary_conditions", "translation in x");
}

// A tiny alpha (2e-6) asked the node search for billions of buckets ("out of memory while building the case");
// an MLS failure in the set-up (here: points no influence domain covers) named no input.
TEST(EfgInput, ShapeFunctionsThatCannotBeBuiltAreAnErrorNamingTheEfgSettings) {
  json j = efg_case();
  j["bodies"][0]["efg"]["alpha"] = 2e-6;
  const Outcome o = run_json("efg_alpha_tiny", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/efg", "shape functions cannot be built");
  EXPECT_NE(o.message.find("enlarge alpha"), std::string::npos) << o.message;
}

// divisions [20, 1e9] ran out of the 20 s a fuzzing run allows (and 1e300 would overflow the int it became).
TEST(EfgInput, ABackgroundGridBeyondWhatARunHoldsIsAnErrorNamingTheDivisions) {
  json j = efg_case();
  for (double n : {1e9, 1e300}) {
    j["bodies"][0]["domain"]["divisions"] = {20, n};
    const Outcome o = run_json("efg_divisions_huge", j);
    EXPECT_EQ(o.code, 2);
    expect_one_line(o, "/bodies/0/domain/divisions", "more than a million");
  }
  j["bodies"][0]["domain"]["divisions"] = {800, 800};
  j["bodies"][0]["efg"]["gauss"] = 4;
  const Outcome o = run_json("efg_points_huge", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/efg/gauss", "integration points");
}

// A region whose box holds no cell's centre left the body's material everywhere, silently.
TEST(EfgInput, ARegionThatTakesNoCellIsAnErrorNamingIt) {
  json j = efg_case();
  j["bodies"][0]["regions"] = json::parse(R"([{"min": [1, 0], "max": [2, 1],
      "material": {"type": "linear_elastic", "young": 500.0, "poisson": 0.3}}])");
  EXPECT_EQ(run_json("efg_region_ok", j).code, 0);
  j["bodies"][0]["regions"][0]["max"] = {1, 1};  // min x = max x: an empty box
  const Outcome o = run_json("efg_region_empty", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/regions/0", "no background cell");
}

// A load of 1e300 overflowed to a non-finite residual; a support of 2^31 node spacings, or a protected segment
// across the body (cutting the part beyond it from the supports), made a singular stiffness ("cholmod: matrix is
// not positive definite"): solver failures with no path. A Young's modulus of 1e-300 was already refused at the
// control (the displacement far beyond the body's size), but blamed the damage laws of a linear elastic body.
TEST(EfgSolve, AStepThatCannotBeSolvedStopsWithOneLineNamingTheControl) {
  json j = efg_case();
  j["bodies"][0]["material"]["young"] = 1e-300;
  Outcome o = run_json("efg_young_tiny", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "/bodies/0/control", "Young's modulus far too small");
  expect_failed_summary(o);
  j = efg_case();
  j["bodies"][0]["efg"]["protected_segments"] = json::parse(R"([{"from": [1.3, -1], "to": [1.3, 2]}])");
  o = run_json("efg_protected_across", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "/bodies/0/control", "cannot be factorized");
  j = efg_case();
  j["bodies"][0]["loads"][0]["value"] = {0, 1e300};
  o = run_json("efg_load_huge", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "/bodies/0/control", "non-finite");
  j = efg_case();
  j["bodies"][0]["efg"]["alpha"] = 2147483648.0;
  o = run_json("efg_alpha_huge", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "/bodies/0/control", "influence domain");
  expect_failed_summary(o);
}

// A residual tolerance of 1e-300 cannot be met: the step reached equilibrium to round-off and the run said
// "Newton did not converge", naming nothing.
TEST(EfgSolve, AToleranceBelowRoundOffIsNamed) {
  json j = efg_case();
  j["analysis"]["newton"]["residual_tolerance"] = 1e-300;
  const Outcome o = run_json("efg_tolerance_roundoff", j);
  EXPECT_EQ(o.code, 3);
  expect_one_line(o, "/analysis/newton/residual_tolerance", "below round-off");
}

// A probe's point that misses every node was reported at /probes/i/at/at (the point selection's own key under
// the probe's "at").
TEST(EfgInput, AProbePointOffTheNodesIsAnErrorNamingItsAt) {
  json j = efg_case();
  j["probes"][0]["at"] = {4.1, 0};
  const Outcome o = run_json("efg_probe_off_nodes", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/probes/0/at: ", "no node within");
  EXPECT_EQ(o.message.find("/at/at"), std::string::npos) << o.message;
}

// A load whose value was left out (zero) under generalized displacement control failed in the first steps with
// "GSP undefined"; under load control every step found the unloaded body and the run reported success.
TEST(EfgInput, ABodyWithNeitherLoadNorPrescribedDisplacementIsAnError) {
  json j = efg_case();
  j["bodies"][0]["loads"][0].erase("value");
  Outcome o = run_json("efg_zero_load", j);
  EXPECT_EQ(o.code, 2);
  expect_one_line(o, "/bodies/0/loads", "neither loaded nor given a displacement");
  // A stretch by a prescribed displacement of the far end, without loads, is a loading.
  j["bodies"][0]["loads"] = json::array();
  j["bodies"][0]["boundary_conditions"].push_back(json::parse(R"({"type": "prescribed", "components": "x",
      "select": {"type": "segment", "from": [4, 0], "to": [4, 1]}, "value": [0.001, 0]})"));
  EXPECT_EQ(run_json("efg_prescribed_only", j).code, 0);
}

}  // namespace
