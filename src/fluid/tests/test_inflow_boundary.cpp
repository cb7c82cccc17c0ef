// The inflow's profiles (src/fluid/inflow_boundary.cpp, a white-box test of its builder): an inflow on the segment
// x = 0, 0 <= y <= H = 0.1 m, mean velocity U = 0.05 m/s along x, spacing h = 0.01 m (N = 10 lanes), driven step by
// step without a flow (an empty cloud: every particle it holds is one it injected, and nothing moves them).
//  - A table of the parabola s (1 - s), in any unit (the inflow divides it by its integral), gives what the built-in
//    parabolic profile gives: the same flux U H t, the same particles at the same places (within what the table's
//    linear interpolation changes: its integral is 1 - 1/M^2 of the parabola's with M intervals).
//  - A table is interpolated linearly and normalized to mean 1: a triangle 0 -> 2 -> 0 holds the particles at
//    s = 1/4 and 1/2 at U and 2 U.
//  - A bad table is refused in one line naming the JSON path of the bad value.
//  - A uniform inflow between walls of particles injects nothing on the wall particles at its ends (the end lanes
//    are left to them), and injects at its ends when no wall particle is there.
//  - Held points ("hold": "points", the default): after the first step one particle sits at each lane's point that
//    has an inflow, held there (its position does not move over a step) at the profile's velocity, and nothing else
//    is held; the new particles enter half a spacing or more in front of the points, at the same rate as with the
//    held layer ("hold": "layer").
#include <gtest/gtest.h>

#include "fluid_boundary.hpp"

#include <lagfsi/error.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::fluid {

std::unique_ptr<FluidBoundary> make_inflow_boundary(Params p, const BoundaryContext& ctx);

namespace {

constexpr double kH = 0.01, kU = 0.05, kHeight = 0.1, kDt = 0.01;

Json inflow_with(const Json& profile) {
  return Json{{"type", "inflow"},
              {"name", "inlet"},
              {"segment", {{0.0, 0.0}, {0.0, kHeight}}},
              {"velocity", {kU, 0.0}},
              {"profile", profile}};
}

std::unique_ptr<FluidBoundary> make(const Json& inflow) {
  return make_inflow_boundary(Params(inflow, "case.json", "/bodies/0/boundaries/0"), {kH, ".", "boundary0"});
}

/// The inflow driven for `steps` steps of kDt from t = 0 into a cloud of the given wall particles: the cloud it
/// filled.
ParticleCloud drive(FluidBoundary& inflow, int steps, const std::vector<Vec2>& walls = {}) {
  ParticleCloud cloud;
  cloud.assign(walls, std::vector<ParticleKind>(walls.size(), ParticleKind::Wall), kH);
  const FluidMesh mesh;
  for (int n = 0; n < steps; ++n) {
    std::vector<BoundaryConstraint> held;
    inflow.constrain(cloud, std::vector<char>(static_cast<size_t>(cloud.n()), 0), n * kDt, held);
    const Vec x_start = cloud.x(), force;
    inflow.after_step({cloud, x_start, (n + 1) * kDt, mesh, force});
  }
  return cloud;
}

/// s (1 - s) at m + 1 points: the parabola's shape, a quarter of the normalized one.
Json parabola_table(int m) {
  Json s = Json::array(), f = Json::array();
  for (int k = 0; k <= m; ++k) {
    const double x = static_cast<double>(k) / m;
    s.push_back(x);
    f.push_back(x * (1 - x));
  }
  return Json{{"type", "table"}, {"s", s}, {"f", f}};
}

/// The one-line error of an inflow with `profile` ("" if it is accepted).
std::string error_of(const Json& profile) {
  try {
    make(inflow_with(profile));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InflowBoundary, ATableOfTheParabolaInjectsTheParabolicProfilesParticlesAndFlux) {
  auto parabolic = make(inflow_with("parabolic"));
  auto table = make(inflow_with(parabola_table(200)));
  const ParticleCloud a = drive(*parabolic, 100), b = drive(*table, 100);
  const Json sa = parabolic->summary(), sb = table->summary();
  // The flux U H t: every profile has mean 1.
  EXPECT_NEAR(sa["area_prescribed"].get<double>(), kU * kHeight * 1.0, 1e-12);
  EXPECT_NEAR(sb["area_prescribed"].get<double>(), sa["area_prescribed"].get<double>(), 1e-12);
  // The same particles, in the same places (the table's values differ from the parabola's by 1/200^2).
  EXPECT_EQ(sb["particles_injected"], sa["particles_injected"]);
  EXPECT_NEAR(sb["area_injected"].get<double>(), sa["area_injected"].get<double>(), 1e-12);
  ASSERT_EQ(a.n(), b.n());
  EXPECT_GT(a.n(), 40);
  // (each lane's phase differs by the 1/200^2 of the distance it travelled, at most 2e-6 m here)
  for (Index i = 0; i < a.n(); ++i) EXPECT_NEAR((a.pos(i) - b.pos(i)).norm(), 0.0, 1e-5) << i;
}

TEST(InflowBoundary, AUniformInflowLeavesItsEndsToTheWallParticlesThere) {
  const std::vector<Vec2> walls = {Vec2(0.0, 0.0), Vec2(0.0, kHeight), Vec2(0.05, 0.0), Vec2(0.05, kHeight)};
  auto between_walls = make(inflow_with("uniform"));
  const ParticleCloud a = drive(*between_walls, 100, walls);
  ASSERT_GT(a.n(), 40);
  for (Index i = 0; i < a.n(); ++i) {
    if (!a.is_fluid(i)) continue;
    for (const Vec2& w : walls) EXPECT_GT((a.pos(i) - w).norm(), 0.5 * kH) << "particle " << i;
  }
  // Without the walls the end lanes inject too: two lanes of N + 1 more.
  auto open = make(inflow_with("uniform"));
  const ParticleCloud b = drive(*open, 100);
  const long with_walls = between_walls->summary()["particles_injected"].get<long>();
  const long without = open->summary()["particles_injected"].get<long>();
  EXPECT_EQ(without - with_walls, 2 * without / (kHeight / kH + 1));
  // Both carry the profile's flux U H t.
  EXPECT_NEAR(between_walls->summary()["area_prescribed"].get<double>(), kU * kHeight * 1.0, 1e-12);
}

TEST(InflowBoundary, ATableIsInterpolatedLinearlyAndNormalizedToMeanOne) {
  // A triangle of peak 7 (any unit): normalized, 0 -> 2 -> 0, mean 1.
  auto inflow = make(inflow_with(Json{{"type", "table"}, {"s", {0.0, 0.5, 1.0}}, {"f", {0.0, 7.0, 0.0}}}));
  ParticleCloud cloud;
  cloud.assign({Vec2(0.0, 0.025), Vec2(0.0, 0.05), Vec2(0.0, 0.1)}, std::vector<ParticleKind>(3, ParticleKind::Fluid),
               kH);
  std::vector<BoundaryConstraint> held;
  inflow->constrain(cloud, std::vector<char>(3, 0), 0.0, held);
  ASSERT_EQ(held.size(), 6u);                                    // both components of the three particles
  EXPECT_NEAR(inflow->velocity(held[0], 0.0), kU * 1.0, 1e-12);  // s = 1/4: half the peak
  EXPECT_NEAR(inflow->velocity(held[2], 0.0), kU * 2.0, 1e-12);  // s = 1/2: the peak, twice the mean
  EXPECT_NEAR(inflow->velocity(held[4], 0.0), 0.0, 1e-12);       // s = 1: zero
  EXPECT_NEAR(inflow->velocity(held[1], 0.0), 0.0, 1e-12);       // the y components
  // The flux is the mean's, U H t.
  drive(*inflow, 10);
  EXPECT_NEAR(inflow->summary()["area_prescribed"].get<double>(), kU * kHeight * 0.1, 1e-12);
}

TEST(InflowBoundary, ATableBeyondItsPointsKeepsItsEndValues) {
  // 1 on [0, 0.5], 0 beyond: mean 1/2 before normalization, so 2 U on the lower half and nothing above.
  auto inflow = make(inflow_with(Json{{"type", "table"}, {"s", {0.25, 0.5, 0.5000001}}, {"f", {1.0, 1.0, 0.0}}}));
  ParticleCloud cloud;
  cloud.assign({Vec2(0.0, 0.01), Vec2(0.0, 0.08)}, std::vector<ParticleKind>(2, ParticleKind::Fluid), kH);
  std::vector<BoundaryConstraint> held;
  inflow->constrain(cloud, std::vector<char>(2, 0), 0.0, held);
  ASSERT_EQ(held.size(), 4u);
  EXPECT_NEAR(inflow->velocity(held[0], 0.0), 2 * kU, 1e-5);
  EXPECT_NEAR(inflow->velocity(held[2], 0.0), 0.0, 1e-12);
}

TEST(InflowBoundary, HeldPointsStayAtTheLanesAndTheNewParticlesEnterInFrontOfThem) {
  Json with_layer = inflow_with("parabolic");
  with_layer["hold"] = "layer";
  auto inflow = make(inflow_with("parabolic")), layer = make(with_layer);
  const ParticleCloud cloud = drive(*inflow, 100);
  drive(*layer, 100);
  // The parabola is zero at the segment's ends: lanes 1 .. N - 1 have points.
  const int lanes = static_cast<int>(std::lround(kHeight / kH));
  std::vector<BoundaryConstraint> held;
  inflow->constrain(cloud, std::vector<char>(static_cast<size_t>(cloud.n()), 0), 1.0, held);
  ASSERT_EQ(held.size(), static_cast<size_t>(2 * (lanes - 1)));
  for (const BoundaryConstraint& k : held) {
    const Vec2 x = cloud.pos(k.i);
    const double s = x.y() / kHeight;
    EXPECT_EQ(x.x(), 0.0) << k.i;
    EXPECT_NEAR(s * lanes, std::round(s * lanes), 1e-12) << k.i;
    EXPECT_EQ(inflow->position(k, 1.0 + kDt), k.base) << k.i;  // held at its point over the step
    EXPECT_NEAR(inflow->velocity(k, 1.0), k.c == 0 ? kU * 6 * s * (1 - s) : 0.0, 1e-12) << k.i;
  }
  // The others are half a spacing or more in front of the segment.
  long in_front = 0;
  for (Index i = 0; i < cloud.n(); ++i)
    if (cloud.pos(i).x() > 0) {
      EXPECT_GE(cloud.pos(i).x(), 0.5 * kH * (1 - 1e-12)) << i;
      ++in_front;
    }
  // Injected at the held layer's rate, and counted alike.
  EXPECT_EQ(in_front, inflow->summary()["particles_injected"].get<long>());
  EXPECT_EQ(inflow->summary()["particles_injected"], layer->summary()["particles_injected"]);
  EXPECT_EQ(inflow->summary()["area_injected"], layer->summary()["area_injected"]);
}

TEST(InflowBoundary, ABuiltInProfileMayBeGivenAsAnObject) {
  EXPECT_EQ(error_of(Json{{"type", "parabolic"}}), "");
  EXPECT_EQ(error_of("uniform"), "");
  EXPECT_NE(error_of(Json{{"type", "parabolic"}, {"s", {0, 1}}}).find("/bodies/0/boundaries/0/profile/s"),
            std::string::npos);
  EXPECT_NE(error_of("cubic").find("/bodies/0/boundaries/0/profile/type: unknown value 'cubic'"), std::string::npos)
      << error_of("cubic");
}

TEST(InflowBoundary, ABadTableIsRefusedNamingThePathOfItsBadValue) {
  const std::string at = "case.json: /bodies/0/boundaries/0/profile/";
  auto table = [](Json s, Json f) { return Json{{"type", "table"}, {"s", s}, {"f", f}}; };
  const std::vector<std::pair<Json, std::string>> bad = {
      {table({0.0, 0.6, 0.5, 1.0}, {1, 1, 1, 1}), at + "s/2: must be greater than the point before it"},
      {table({0.0, 0.5, 0.5}, {1, 1, 1}), at + "s/2: must be greater than the point before it"},
      {table({-0.1, 1.0}, {1, 1}), at + "s/0: must lie in [0, 1] (found -0.1)"},
      {table({0.0, 1.5}, {1, 1}), at + "s/1: must lie in [0, 1] (found 1.5)"},
      {table({0.0, 0.5, 1.0}, {1, 1}), at + "f: has 2 values for 3 points in s"},
      {table({0.0, 1.0}, {1, -1}), at + "f/1: must not be negative (found -1)"},
      {table({0.5}, {1}), at + "s: needs at least two points"},
      {table({0.0, 1.0}, {0, 0}), at + "f: must not be zero everywhere (the flux would be zero)"},
      {table({0.0, "a"}, {1, 1}), at + "s/1: expected a finite number"},
      {Json{{"type", "table"}, {"s", {0.0, 1.0}}}, at + "f: required key is missing"}};
  for (const auto& [profile, message] : bad) EXPECT_EQ(error_of(profile), message) << profile.dump();
}

}  // namespace
}  // namespace lagfsi::fluid
