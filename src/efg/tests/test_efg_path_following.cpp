// EFG path following, the control's own rules: load control refuses a step past a limit point (the tangent
// response to the load turned against the last step's) with a message that names the control's JSON path; a
// negative arc length is a direction (the first step against the reference load, the later ones along the path from
// there, mirroring a positive one); the control's memory written to a checkpoint and read back gives the same next
// steps.
#include <lagfsi/efg/path_following.hpp>
#include <lagfsi/error.hpp>

#include <gtest/gtest.h>

#include <string>

using namespace lagfsi;
using namespace lagfsi::efg;

namespace {
Vec v2(double a, double b) {
  Vec v(2);
  v << a, b;
  return v;
}
}  // namespace

TEST(EfgPathFollowing, LoadControlPastTheLimitPointStopsWithAnError) {
  PathFollowing pf(ControlType::load, 0.5, -1);
  pf.locate("/bodies/0/control");
  // Two steps on the stiffening-then-softening branch before the peak: the response grows, keeps its direction.
  for (const Vec& d : {v2(1.0, 0.2), v2(3.0, 0.5)}) {
    const double dl = pf.predictor(d, 1.0);
    EXPECT_DOUBLE_EQ(dl, 0.5);
    pf.commit(dl * d);
  }
  EXPECT_DOUBLE_EQ(pf.load_factor(), 1.0);
  // Past the peak the tangent response to the load points back (the stiffness is no longer positive definite).
  try {
    pf.predictor(v2(-2.0, -0.1), 1.0);
    FAIL() << "a step past the limit point was taken under load control";
  } catch (const SolverError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("/bodies/0/control: load control cannot pass the limit point at load factor 1 ", 0), 0u) << m;
    EXPECT_NE(m.find("arc_length"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(EfgPathFollowing, NegativeArcLengthStartsAgainstTheLoadAndMirrorsAPositiveOne) {
  // The same tangent responses (a softening, then reversing path) with +0.1 and -0.1: every load-factor
  // increment of the negative one is the opposite of the positive one's, and the arc length the same.
  PathFollowing pos(ControlType::arc_length, 0.1, -1), neg(ControlType::arc_length, -0.1, -1);
  const Vec responses[] = {v2(1.0, 0.5), v2(2.0, 0.8), v2(-4.0, -1.0), v2(-3.0, -0.5)};
  bool reversed = false;
  for (const Vec& d : responses) {
    const double lp = pos.predictor(d, 1.0), ln = neg.predictor(d, 1.0);
    EXPECT_EQ(ln, -lp);
    // One corrector iteration on the constraint: the root closest to the step's direction, mirrored too.
    const Vec dUQ = v2(0.01, -0.02);
    const double cp = pos.corrector(d, dUQ, lp * d), cn = neg.corrector(d, -dUQ, ln * d);
    EXPECT_NEAR(cn, -cp, 1e-15 * (1 + std::abs(cp)));
    pos.commit(lp * d + cp * d + dUQ);
    neg.commit(ln * d + cn * d - dUQ);
    reversed = reversed || lp < 0;
  }
  EXPECT_TRUE(reversed);  // the path passed a limit point: the sign of the steps came from the path, not the input
  EXPECT_LT(neg.load_factor(), 0.0);
  EXPECT_EQ(pos.stats().steps_off_constraint, 0);
  EXPECT_EQ(neg.stats().steps_off_constraint, 0);
}

TEST(EfgPathFollowing, ACheckpointedControlTakesTheSameNextStep) {
  for (ControlType t : {ControlType::generalized_displacement, ControlType::arc_length}) {
    PathFollowing a(t, 0.1, -1);
    for (const Vec& d : {v2(1.0, 0.5), v2(2.0, 0.8), v2(-4.0, -1.0)}) a.commit(a.predictor(d, 1.0) * d);
    StateArchive out;
    a.serialize(out);
    PathFollowing b(t, 0.1, -1);
    StateArchive in(out.data());
    b.serialize(in);
    EXPECT_TRUE(in.at_end());
    const Vec d = v2(-3.0, -0.5);
    EXPECT_EQ(b.predictor(d, 0.5), a.predictor(d, 0.5));
    EXPECT_EQ(b.corrector(d, v2(0.01, 0.0), 0.1 * d), a.corrector(d, v2(0.01, 0.0), 0.1 * d));
    EXPECT_EQ(b.load_factor(), a.load_factor());
  }
}
