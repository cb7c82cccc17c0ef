// The PFEM fluid's wall particles keep the fluid in (WallParticles::keep_inside_walls, a white-box test of the
// private src/fluid/fluid_walls.hpp): a particle whose step ends deeper than the tolerance (0.5 h for a particle in
// no element with a wall particle) in the solid behind the walls (its distance to their nearest point) is put back
// on the fluid side there.
//  - A film sliding along a tank's floor a little below it leaves through the corner, where it is past the end
//    of both segments: it goes back to the corner (before, it was in neither span and left the tank: the
//    dam break with the level-set detection lost water there).
//  - The same at a corner between two walls (a cylinder and the plate behind it, Turek & Hron's channel): a
//    particle the recirculation pushes into the corner goes back (before, past the end of either wall's segment,
//    it slid into the plate, and the mesh filled the solid).
//  - A particle falling past the outside corner of an obstacle is not pulled onto the obstacle's top: past a
//    segment's end only counts where the particle is beyond the neighbouring segment too.
//  - The fluid side of a segment the initial fluid cannot see (an obstacle's downstream face, hidden by the
//    obstacle) is its neighbours' along the polyline; a particle sliding along the floor into the obstacle's
//    foot is then put on that face (WallContacts::snap_to_walls), not let through it.
//  - Of a flap hinged on a floor, only the floor's line is a fixed wall's (FluidWalls::along_fixed).
#include <gtest/gtest.h>

#include "fluid_mesh.hpp"
#include "fluid_walls.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace lagfsi::fluid {
namespace {

constexpr double kH = 0.0073;

template <class W>
struct WallScene {
  W walls;
  ParticleCloud cloud;
  FluidMesh mesh;  // no elements: no particle is held by a wall particle's element
};

// Walls from JSON; the fluid side of each segment from the fluid particles `fluid` (the tested particle is the
// cloud's last, at `start`).
template <class W>
void make(WallScene<W>& s, const Json& walls, const std::vector<Vec2>& fluid, const Vec2& start) {
  s.walls.read(Params(walls, "test.json", "/bodies/0/walls"), kH, ".");
  std::vector<Vec2> pts = fluid;
  std::vector<ParticleKind> kind(fluid.size(), ParticleKind::Fluid);
  s.walls.set_fluid_sides(pts, kind);
  pts.push_back(start);
  kind.push_back(ParticleKind::Fluid);
  s.cloud.assign(pts, kind, kH);
}

// The tested particle's step from `start` to `end`; returns where keep_inside_walls leaves it.
Vec2 step(WallScene<WallParticles>& s, const Vec2& end) {
  const Index i = s.cloud.n() - 1;
  const Vec x_start = s.cloud.x();
  s.cloud.x().segment<2>(2 * i) = end;
  s.cloud.v().segment<2>(2 * i) = Vec2(2.8, -0.2);
  s.walls.keep_inside_walls(s.cloud, s.mesh, x_start, 0.0);
  return s.cloud.x().segment<2>(2 * i);
}

TEST(FluidWalls, AFilmBelowTheFloorDoesNotLeaveThroughTheTanksCorner) {
  WallScene<WallParticles> s;
  const Json tank = Json::array({{{"name", "tank"}, {"points", {{0, 0.584}, {0, 0}, {0.584, 0}, {0.584, 0.584}}}}});
  // Below the floor by 2 mm (< 0.5 h: left alone), ending 5 mm beyond the right wall's line and below the
  // floor (past the right wall's lower end).
  make(s, tank, {{0.1, 0.1}, {0.3, 0.2}, {0.5, 0.05}}, {0.581, -0.002});
  const Vec2 p = step(s, {0.589, -0.002});
  EXPECT_LT(p.x(), 0.584);
  EXPECT_GE(p.y(), -0.002);
  const double r = 0.05 * kH / std::sqrt(2.0);  // at the corner, 0.05 h along its bisector on the fluid side
  EXPECT_NEAR(p.x(), 0.584 - r, 1e-12);
  EXPECT_NEAR(p.y(), r, 1e-12);
  EXPECT_LT(s.cloud.v().segment<2>(2 * (s.cloud.n() - 1)).dot(Vec2(-1, 1)), 1e-12);  // no velocity into the walls
  EXPECT_EQ(s.walls.crossings(), 1);
}

TEST(FluidWalls, AParticlePushedIntoACornerBetweenTwoWallsGoesBack) {
  WallScene<WallParticles> s;
  // A post (x = 0.1) with a plate 0.02 m thick behind it, the plate a wall of its own whose ends meet the post's.
  const Json walls = Json::array({{{"name", "post_top"}, {"points", {{0.1, 0.3}, {0.1, 0.11}}}},
                                  {{"name", "plate"}, {"points", {{0.1, 0.11}, {0.3, 0.11}, {0.3, 0.09}, {0.1, 0.09}}}},
                                  {{"name", "post_bottom"}, {"points", {{0.1, 0.09}, {0.1, -0.1}}}}});
  make(s, walls, {{0.2, 0.2}, {0.2, 0.0}, {0.4, 0.1}}, {0.102, 0.1115});
  // From the corner's fluid side to 4 mm left of the post's line and 6 mm below the plate's top: past the end of
  // every segment near it, 0.99 h from the corner.
  const Vec2 p = step(s, {0.096, 0.104});
  const double r = 0.05 * kH / std::sqrt(2.0);
  EXPECT_NEAR(p.x(), 0.1 + r, 1e-12);
  EXPECT_NEAR(p.y(), 0.11 + r, 1e-12);
  EXPECT_EQ(s.walls.crossings(), 1);
}

TEST(FluidWalls, AParticleLessThanHalfASpacingBehindAWallIsLeftAlone) {
  WallScene<WallParticles> s;
  const Json tank = Json::array({{{"name", "tank"}, {"points", {{0, 0.584}, {0, 0}, {0.584, 0}, {0.584, 0.584}}}}});
  make(s, tank, {{0.1, 0.1}, {0.3, 0.2}, {0.5, 0.05}}, {0.3, 0.001});
  const Vec2 p = step(s, {0.31, -0.45 * kH});  // a film's particle dipping below the floor
  EXPECT_DOUBLE_EQ(p.y(), -0.45 * kH);
  EXPECT_EQ(s.walls.crossings(), 0);
}

TEST(FluidWalls, AParticleFallingPastAnObstaclesCornerStaysBesideIt) {
  WallScene<WallParticles> s;
  const Json box = Json::array({{{"name", "box"}, {"points", {{0.3, 0.0}, {0.3, 0.1}, {0.4, 0.1}, {0.4, 0.0}}}}});
  // Fluid above the box and on both sides of it.
  make(s, box, {{0.35, 0.2}, {0.2, 0.05}, {0.5, 0.05}}, {0.403, 0.102});
  const Vec2 p = step(s, {0.403, 0.09});  // 3 mm right of the top's end, 10 mm below its line
  EXPECT_DOUBLE_EQ(p.x(), 0.403);
  EXPECT_DOUBLE_EQ(p.y(), 0.09);
  EXPECT_EQ(s.walls.crossings(), 0);
}

TEST(FluidWalls, AnObstaclesHiddenFaceTakesItsNeighboursFluidSide) {
  // Walls as constraints that put a particle arriving at a wall on it within 0.1 h.
  WallScene<WallContacts> s{WallContacts(kH, 0.1, Vec2(0, -9.81), 0.0), {}, {}};
  // cases/dam_break_obstacle: the obstacle is a bump of the tank's polyline, the water a column left of it.
  const Json tank = Json::array(
      {{{"name", "tank"},
        {"points",
         {{0, 0.584}, {0, 0}, {0.280, 0}, {0.280, 0.048}, {0.304, 0.048}, {0.304, 0}, {0.584, 0}, {0.584, 0.584}}}}});
  make(s, tank, {{0.05, 0.01}, {0.1, 0.03}, {0.1, 0.2}}, {0.3074, 0.0});
  const auto& w = s.walls.all().front();
  EXPECT_EQ(w.fluid_normal(2), Vec2(-1, 0));  // the upstream face, seen by the column
  EXPECT_EQ(w.fluid_normal(3), Vec2(0, 1));   // the top and the downstream face, seen by none: their neighbours'
  EXPECT_EQ(w.fluid_normal(4), Vec2(1, 0));   // (before, the column facing it through the obstacle: -x)
  EXPECT_EQ(w.fluid_normal(5), Vec2(0, 1));
  EXPECT_EQ(w.fluid_normal(6), Vec2(-1, 0));  // the right wall, seen across the tank
  // A particle on the floor sliding left at 4.6 m/s (1 ms) into the obstacle's foot goes onto the face.
  const Index i = s.cloud.n() - 1;
  const Vec x_start = s.cloud.x();
  s.cloud.x().segment<2>(2 * i) = Vec2(0.30283, 0.0);
  s.cloud.v().segment<2>(2 * i) = Vec2(-4.6, 0.0);
  s.walls.snap_to_walls(s.cloud, x_start, 0.0);
  EXPECT_NEAR(s.cloud.x()[2 * i], 0.304, 1e-12);
  EXPECT_NEAR(s.cloud.x()[2 * i + 1], 0.0, 1e-12);
  EXPECT_NEAR(s.cloud.v()[2 * i], 0.0, 1e-12);  // its velocity into the face is gone
  EXPECT_EQ(s.walls.crossings(), 1);
}

// A flap: a wall turning about its foot by theta(t) = -0.2 t rad (clockwise; a ramp from 0 to 1 over 1 s).
const Json kFlap = Json::array({{{"name", "flap"},
                                 {"points", {{0, 0}, {0, 0.1}}},
                                 {"slip", true},
                                 {"motion",
                                  {{"type", "prescribed_rotation"},
                                   {"pivot", {0, 0}},
                                   {"value", -0.2},
                                   {"function", {{"type", "ramp"}, {"t0", 0}, {"t1", 1}}}}}}});

TEST(FluidWalls, AFlapsParticlesTurnAboutItsHingeWithItsAngularVelocity) {
  WallParticles walls;
  walls.read(Params(kFlap, "test.json", "/bodies/0/walls"), kH, ".");
  std::vector<Vec2> pts;
  std::vector<ParticleKind> kind;
  PointGrid grid(0.5 * kH);
  walls.place_particles(Params(kFlap, "test.json", "/bodies/0/walls"), kH, pts, kind, grid);
  const Index n = static_cast<Index>(pts.size());
  Vec X0(2 * n), x(2 * n), v(2 * n), a(2 * n);
  for (Index j = 0; j < n; ++j) X0.segment<2>(2 * j) = pts[static_cast<size_t>(j)];
  walls.place_own(0.5, X0, x);
  walls.move_own(0.5, v, a);
  const double th = -0.1, w = -0.2;  // the angle at t = 0.5 s and its rate
  for (Index j = 0; j < n; ++j) {
    const double r = X0[2 * j + 1];  // the particle's height on the upright flap
    EXPECT_NEAR(x[2 * j], -r * std::sin(th), 1e-12);
    EXPECT_NEAR(x[2 * j + 1], r * std::cos(th), 1e-12);
    EXPECT_NEAR(v[2 * j], -w * r * std::cos(th), 1e-8);  // omega x r: (-w r_y, w r_x)
    EXPECT_NEAR(v[2 * j + 1], -w * r * std::sin(th), 1e-8);
  }
}

TEST(FluidWalls, AParticleOnATurningWallFollowsItAndStaysOnItsLine) {
  WallContacts walls(kH, 0.1, Vec2(0, -9.81), 0.0);
  walls.read(Params(kFlap, "test.json", "/bodies/0/walls"), kH, ".");
  ParticleCloud cloud;
  cloud.assign({{0.03, 0.05}, {0.0, 0.05}}, {ParticleKind::Fluid, ParticleKind::Fluid}, kH);
  walls.set_fluid_sides(cloud.positions(), cloud.kind());
  walls.find(cloud, 0.0);
  ASSERT_EQ(walls.constraints().size(), 1u) << "the particle on the flap, in the flap's frame";
  const BoundaryConstraint k = walls.constraints()[0];
  EXPECT_EQ(k.i, 1);
  EXPECT_EQ(walls.frames()->direction(1, 0), Vec2(1, 0)) << "the flap's normal towards its fluid";
  // At t = 0.5 s the flap's point under the particle is at r (sin 0.1, cos 0.1): its normal coordinate is the
  // prescribed one.
  EXPECT_NEAR(walls.position(k, 0.5), 0.05 * std::sin(0.1), 1e-12);
  EXPECT_NEAR(walls.velocity(k, 0.5), 0.2 * 0.05 * std::cos(0.1), 1e-8);
  // A particle that slid along the frame's line ends off the turned flap; it is put back on the flap's line.
  cloud.x().segment<2>(2) = Vec2(walls.position(k, 0.5), 0.07);
  walls.follow_turning_walls(cloud, 0.5);
  const Vec2 p = cloud.pos(1), n1(std::cos(0.1), -std::sin(0.1));  // the flap's normal at 0.5 s
  EXPECT_NEAR(n1.dot(p), 0.0, 1e-12);
}

TEST(FluidWalls, OnlyTheLinesOfWallsThatDoNotMoveAreFixedLines) {
  // A flap hinged on a floor: a point on either lies along the walls; only the floor's is along a fixed wall (the
  // domain detection leaves water against a wall only there).
  Json walls_json = kFlap;
  walls_json.push_back({{"name", "floor"}, {"points", {{0, 0}, {0.5, 0}}}, {"slip", true}});
  WallContacts walls(kH, 0.1, Vec2(0, -9.81), 0.0);
  walls.read(Params(walls_json, "test.json", "/bodies/0/walls"), kH, ".");
  ParticleCloud cloud;
  cloud.assign({{0.03, 0.05}, {0.0, 0.05}, {0.2, 0.0}}, std::vector<ParticleKind>(3, ParticleKind::Fluid), kH);
  walls.set_fluid_sides(cloud.positions(), cloud.kind());
  walls.find(cloud, 0.0);
  EXPECT_TRUE(walls.along({0.0, 0.05}));
  EXPECT_FALSE(walls.along_fixed({0.0, 0.05})) << "on the flap";
  EXPECT_TRUE(walls.along({0.2, 0.0}));
  EXPECT_TRUE(walls.along_fixed({0.2, 0.0})) << "on the floor";
  EXPECT_FALSE(walls.along({0.03, 0.05}));
  EXPECT_FALSE(walls.along_fixed({0.03, 0.05})) << "in the water";
}

TEST(FluidWalls, AFixedMeshsWallsDoNotTurn) {
  FixedMeshWalls walls;
  try {
    walls.read(Params(kFlap, "test.json", "/bodies/0/walls"), kH, ".");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/bodies/0/walls/0/motion/type"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagfsi::fluid
