// Retry-safe predict: the driver retries a failed step from the same state with half the step
// (analysis.cpp: predict again before finalize_step). For each model the test makes an attempt that fails
// part of the way (a first predict with dt and one solve_iteration, which for the solid and the fluid is one
// Newton correction and for the MPM and the DEM the whole sub-stepped step: the most the attempt can have
// advanced), then
// retries with dt / 2, and checks that the retried step and the step after it give exactly (bit for bit) the
// probes of a clean run at dt / 2. A predict that did not restore the start of the step fails it.
#include <lagfsi/app/model_registry.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace lagfsi;

CaseContext context(double dt) {
  CaseContext c;
  c.case_file = "test_retry.json";
  c.base_dir = ".";
  c.out_dir = std::filesystem::temp_directory_path() / "lagfsi_test_retry";
  c.analysis.type = "dynamic";
  c.analysis.dt = dt;
  c.analysis.end_time = 10 * dt;
  c.analysis.integrator = IntegratorSpec{};  // Newmark, beta 1/4, gamma 1/2
  c.analysis.linear_solver.type = "umfpack";
  c.gravity = Vec2(0.0, -9.81);
  c.quiet = true;
  return c;
}

/// Two steps (dt / 2 and dt) after an optional failed attempt at dt; the probes after each step.
std::vector<double> run(const Json& body, const std::vector<Json>& probes, double dt, bool failed_attempt) {
  const CaseContext ctx = context(dt);
  auto m = model_registry().at(body["type"])(Params(body, "test_retry.json", "/bodies/0"), ctx);
  std::vector<std::unique_ptr<Probe>> ps;
  for (const Json& p : probes) ps.push_back(m->make_probe(Params(p, "test_retry.json", "/probes/0")));
  m->initialize();
  std::vector<double> out;
  double t = 0;
  for (double h : {0.5 * dt, dt}) {
    if (failed_attempt && t == 0) {
      m->predict(t + dt, dt);
      (void)m->solve_iteration();  // the attempt stops here, as a SolverError would stop it
    }
    m->predict(t + h, h);
    iterate_to_convergence(*m, 25, t + h);
    m->finalize_step();
    t += h;
    for (const auto& p : ps)
      for (double v : p->sample()) out.push_back(v);
  }
  return out;
}

void expect_retry_equals_clean(const Json& body, const std::vector<Json>& probes, double dt) {
  const std::vector<double> clean = run(body, probes, dt, false);
  const std::vector<double> retried = run(body, probes, dt, true);
  ASSERT_EQ(clean.size(), retried.size());
  bool moved = false;
  for (size_t i = 0; i < clean.size(); ++i) {
    EXPECT_EQ(clean[i], retried[i]) << "probe value " << i;
    moved = moved || clean[i] != 0.0;
  }
  EXPECT_TRUE(moved) << "the body did not move: the test would not see a state left by the failed attempt";
}

TEST(Retry, SolidRetriedStepEqualsACleanStep) {
  const Json body = Json::parse(R"({"name": "beam", "type": "solid", "gravity": true,
    "material": {"type": "svk", "young": 1e5, "density": 1000},
    "geometry": {"type": "rectangle", "origin": [0, 0], "size": [1, 0.1]},
    "mesh": {"type": "structured", "size": 0.1, "divisions": [8, 1], "order": 2},
    "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0, 0.1]}}]})");
  expect_retry_equals_clean(body,
                            {Json{{"name", "tip"}, {"type", "displacement"}, {"body", "beam"}, {"at", {1.0, 0.1}}},
                             Json{{"name", "ke"}, {"type", "energy"}, {"body", "beam"}, {"kind", "kinetic"}}},
                            0.05);
}

TEST(Retry, FluidRetriedStepEqualsACleanStep) {
  // Remeshed every step: the retry must not remesh a second time.
  const Json body = Json::parse(R"({"name": "water", "type": "fluid", "density": 1000, "viscosity": 1e-3,
    "spacing": 0.02, "alpha": 1.2,
    "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.1, 0.2]}],
    "walls": [{"name": "floor", "points": [[0, 0.4], [0, 0], [0.5, 0]]}],
    "initial_pressure": {"type": "hydrostatic", "level": 0.2}})");
  expect_retry_equals_clean(body,
                            {Json{{"name", "ke"}, {"type", "kinetic_energy"}, {"body", "water"}},
                             Json{{"name", "area"}, {"type", "fluid_area"}, {"body", "water"}}},
                            0.004);
}

TEST(Retry, MpmRetriedStepEqualsACleanStep) {
  const Json body = Json::parse(R"({"name": "column", "type": "mpm",
    "material": {"type": "linear_elastic", "young": 1.0e6, "poisson": 0.0, "density": 1800.0},
    "grid": {"origin": [0, 0], "size": [0.005, 0.12], "cell": 0.005},
    "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.005, 0.1]}],
    "particles_per_cell": 2, "update": "musl",
    "boundary_conditions": [
      {"type": "fixed", "select": {"type": "all"}, "components": "x"},
      {"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0.005, 0]}, "components": "y"}]})");
  expect_retry_equals_clean(body,
                            {Json{{"name", "uy"},
                                  {"type", "particle"},
                                  {"body", "column"},
                                  {"at", {0.00125, 0.09875}},
                                  {"quantity", "displacement_y"}},
                             Json{{"name", "ke"}, {"type", "energy"}, {"body", "column"}, {"kind", "kinetic"}}},
                            2e-3);
}

TEST(Retry, DemRetriedStepEqualsACleanStep) {
  // A bed falling on a floor with friction (tangential histories), pushed by a moving wall and loaded by a blast
  // whose exposure is recomputed every third call: the failed attempt rebuilds and reorders the lists, moves the
  // wall, advances the blast's call count and the energy counters, all of which the retry must undo.
  const Json body = Json::parse(R"({"name": "bed", "type": "dem", "material": {"density": 2500},
    "contact": {"law": "linear", "kn": 1e5, "damping_ratio": 0.1, "friction": 0.5},
    "discs": [{"type": "hex_lattice", "region": {"type": "rectangle", "origin": [0, 0], "size": [0.05, 0.02]},
               "radius": 0.002, "velocity": [0, -0.5]}],
    "walls": [{"name": "box", "points": [[0, 0.2], [0, 0], [0.1, 0]]},
              {"name": "piston", "points": [[0.0505, 0], [0.0505, 0.05]], "velocity": [-0.5, 0]}],
    "blast": {"charge_mass": 0.001, "position": [0.025, 0.5], "exposure_every": 3},
    "time_step": {"dt": 2e-5}})");
  expect_retry_equals_clean(body,
                            {Json{{"name", "y0"}, {"type", "disc"}, {"body", "bed"}, {"id", 0}, {"quantity", "y"}},
                             Json{{"name", "w0"}, {"type", "disc"}, {"body", "bed"}, {"id", 0}, {"quantity", "omega"}},
                             Json{{"name", "vx"}, {"type", "disc"}, {"body", "bed"}, {"id", 11}, {"quantity", "vx"}},
                             Json{{"name", "fmax"}, {"type", "max_contact_force"}, {"body", "bed"}},
                             Json{{"name", "balance"}, {"type", "energy"}, {"body", "bed"}, {"kind", "balance"}},
                             Json{{"name", "blast"}, {"type", "energy"}, {"body", "bed"}, {"kind", "blast_work"}}},
                            2e-3);
}

}  // namespace
