// The fluid's systems through the PETSc Krylov solvers (src/core/petsc_solver.cpp) against the direct path: the
// default dam break over 0.3 s (through the impact) gives the direct solver's probes to 1e-6 relative under
// both schemes, and a solid's dynamic response through CG + GAMG (with the rigid-body modes) or MUMPS gives
// CHOLMOD's; a Krylov solve that cannot converge fails the step, the step retry takes over and the run ends
// with the solver's reason; summary.json reports the iterations per solve.
#include "case_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using namespace lagfsi::testing;

const char* kCase = "cases/dam_break_tank/case.json";

/// Largest difference of each probe over the run, relative to the probe's largest magnitude.
void expect_same_probes(const RunResult& a, const RunResult& b, double tol) {
  const Csv pa = probes_of(a), pb = probes_of(b);
  ASSERT_EQ(pa.rows(), pb.rows());
  ASSERT_GT(pa.rows(), 10u);
  for (const std::string& name : pa.header) {
    // An energy balance is a difference of energies: its round-off is on the energies' scale.
    const std::string& scale_of = name == "energy_balance" ? std::string("energy_total") : name;
    double scale = 0.0, diff = 0.0;
    for (size_t i = 0; i < pa.rows(); ++i) {
      scale = std::max(scale, std::abs(pa[scale_of][i]));
      diff = std::max(diff, std::abs(pa[name][i] - pb[name][i]));
    }
    EXPECT_LE(diff, tol * std::max(scale, 1e-300)) << name;
  }
}

void expect_krylov_equals_direct(const std::string& scheme, const std::string& tag) {
  const std::vector<std::string> common = {"analysis.end_time=0.3", "output.vtk=false",
                                           "bodies.0.scheme.type=" + scheme};
  auto with = [&](const std::string& solver) {
    std::vector<std::string> s = common;
    s.push_back("bodies.0.scheme.linear_solver=" + solver);
    return s;
  };
  const RunResult direct = run_case_file(kCase, tag + "_direct", with(scheme == "fractional_step" ? "cholmod" : "klu"));
  const RunResult krylov = run_case_file(kCase, tag + "_petsc", with("petsc"));
  ASSERT_EQ(direct.exit_code, 0) << direct.stderr_text;
  ASSERT_EQ(krylov.exit_code, 0) << krylov.stderr_text;
  expect_same_probes(direct, krylov, 1e-6);
  const auto solvers = summary_of(krylov)["bodies"][0]["linear_solvers"];
  const auto& main = solvers.contains("newton") ? solvers["newton"] : solvers["pressure"];
  EXPECT_EQ(main["type"], "petsc");
  EXPECT_GT(main["iterations_per_solve"].get<double>(), 0.0);
  EXPECT_EQ(main["failures"].get<long>(), 0);
  EXPECT_EQ(summary_of(direct)["bodies"][0]["linear_solvers"].begin()->value("krylov_solves", 0L), 0);
}

TEST(KrylovSolvers, TheMonolithicDamBreakThroughTheImpactEqualsTheDirectPath) {
  expect_krylov_equals_direct("monolithic_pspg", "krylov_pspg");
}

TEST(KrylovSolvers, TheFractionalStepDamBreakThroughTheImpactEqualsTheDirectPath) {
  expect_krylov_equals_direct("fractional_step", "krylov_fs");
}

TEST(KrylovSolvers, ASolidThroughMultigridWithRigidBodyModesOrMumpsEqualsCholmod) {
  const char* cantilever = "cases/cantilever_step_load/case.json";
  const std::vector<std::string> sets = {"analysis.end_time=0.02", "output.vtk=false"};
  auto with = [&](const std::string& solver) {
    std::vector<std::string> s = sets;
    s.push_back("analysis.linear_solver=" + solver);
    return s;
  };
  const RunResult direct = run_case_file(cantilever, "krylov_solid_cholmod", with("cholmod"));
  ASSERT_EQ(direct.exit_code, 0) << direct.stderr_text;
  for (const std::string solver : {"petsc", "mumps"}) {
    const RunResult r = run_case_file(cantilever, "krylov_solid_" + solver, with(solver));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    expect_same_probes(direct, r, 1e-6);
    EXPECT_EQ(summary_of(r)["bodies"][0]["linear_solver"]["method"], solver == "petsc" ? "cg/gamg" : "mumps");
  }
}

TEST(KrylovSolvers, ASolveThatDoesNotConvergeFailsTheStepAndTheRetryTakesOver) {
  const RunResult r =
      run_case_file(kCase, "krylov_fails",
                    {"analysis.end_time=0.01", "analysis.max_step_halvings=2", "output.vtk=false",
                     R"(bodies.0.scheme.linear_solver={"type": "petsc", "pc": "none", "max_iterations": 2})"});
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("iteration limit reached after 2 iterations"), std::string::npos) << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
  const auto s = summary_of(r);
  // The first step, then its two halvings: three failed solves.
  EXPECT_EQ(s["bodies"][0]["linear_solvers"]["newton"]["failures"].get<long>(), 3) << s.dump(2);
}

}  // namespace
