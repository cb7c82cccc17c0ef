// EFG path following on a whole body: a run that cannot follow its path stops with one line naming the control's
// JSON path and a solver-failure exit code, never a "completed" run over an absurd state. The Mazars plate in
// tension (peak lambda = 2.0; its damage keeps a residual stress and the clamp D <= 1 - 1e-9 a residual stiffness,
// so a load above the peak still finds an "equilibrium", far beyond the plate's size): load control
// driven past the peak; an initial load factor so large that the first step lands on that residual stiffness; a
// displacement-control increment as large as the body, refused at input.
#include "case_runner.hpp"

#include <algorithm>
#include <cmath>

using namespace lagfsi::testing;

namespace {

const char* kPlate = "cases/efg_tension_plate/case.json";

std::vector<std::string> coarse_plate(std::vector<std::string> extra) {
  std::vector<std::string> s = {"bodies.0.domain.divisions=[4,4]", "bodies.0.efg.gauss=6", "analysis.load_steps=30",
                                "output.vtk=false"};
  s.insert(s.end(), extra.begin(), extra.end());
  return s;
}

size_t lines(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST(EfgPathFollowingRuns, LoadControlPastTheLimitPointStopsWithAnError) {
  // lambda to 3 in steps of 0.1: the step beyond the peak (2.0) is refused; the probes end at the peak.
  const RunResult r = run_case_file(kPlate, "efg_pf_load",
                                    coarse_plate({"bodies.0.control.type=load", "bodies.0.control.increment=0.1"}));
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json: /bodies/0/control: load control past the limit point"), std::string::npos)
      << r.stderr_text;
  const Csv c = read_csv(r.out_dir / "probes.csv");
  EXPECT_NEAR(c["lambda"].back(), 2.0, 0.02);
  for (double u : c["u_A"]) EXPECT_LT(std::abs(u), 1.0);  // no absurd state was committed (the plate is 1 m)
}

TEST(EfgPathFollowingRuns, AnIncrementFarTooLargeStopsWithAnError) {
  // An arc length from an initial load factor of 1e6 (5e5 times the peak): the first step is refused.
  const RunResult r = run_case_file(
      kPlate, "efg_pf_runaway", coarse_plate({"bodies.0.control.type=arc_length", "bodies.0.control.increment=1e6"}));
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json: /bodies/0/control/increment: runaway step"), std::string::npos)
      << r.stderr_text;
  const Csv c = read_csv(r.out_dir / "probes.csv");
  EXPECT_EQ(c.rows(), 1u);  // the initial state only
}

TEST(EfgPathFollowingRuns, ADisplacementIncrementAsLargeAsTheBodyIsRefusedAtInput) {
  const RunResult r = run_case_file(kPlate, "efg_pf_du",
                                    coarse_plate({"bodies.0.control.type=displacement", "bodies.0.control.at=[1,0.5]",
                                                  "bodies.0.control.component=x", "bodies.0.control.increment=-2"}));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_EQ(lines(r.stderr_text), 1u) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("case.json: /bodies/0/control/increment: a displacement increment of 2"),
            std::string::npos)
      << r.stderr_text;
}
