// The pressure level of water that no boundary sets (src/fluid/pressure_level.hpp, white box): two triangles of
// water apart, under gravity -y.
//  - The one with a free-surface particle keeps its level; the enclosed one gets p = 0 at its highest particle.
//  - With a bulk modulus nothing is pinned: the compressible continuity sets the level.
//  - An inflow's particles set no level (not even those marked free surface at the inlet's ends): an enclosed part
//    an inflow feeds is reported with that inflow, and nothing is pinned in it.
#include <gtest/gtest.h>

#include "pressure_level.hpp"

#include <vector>

namespace lagfsi::fluid {
namespace {

struct TwoParts {
  ParticleCloud cloud;
  FluidMesh mesh;
  std::vector<std::uint8_t> free = std::vector<std::uint8_t>(6, 0);
  std::vector<int> inflow = std::vector<int>(6, -1);
  std::vector<char> fixed = std::vector<char>(18, 0);
  TwoParts() {
    cloud.assign({Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(5, 0), Vec2(6, 0), Vec2(5.5, 2)},
                 std::vector<ParticleKind>(6, ParticleKind::Fluid), 0.5);
    mesh.tri = {{0, 1, 2}, {3, 4, 5}};
    free[2] = 1;  // the first part's top is on the free surface
  }
  PressureLevelParts anchor(double bulk) {
    return anchor_pressure_level(mesh, cloud, free, inflow, Vec2(0, -9.81), bulk, fixed);
  }
  std::vector<char> pressure_fixed() const { return {fixed[2], fixed[5], fixed[8], fixed[11], fixed[14], fixed[17]}; }
};

TEST(PressureLevel, AnEnclosedPartIsPinnedAtItsHighestParticleAndAFreeOneIsLeftAlone) {
  TwoParts s;
  const PressureLevelParts r = s.anchor(0.0);
  EXPECT_EQ(r.pinned, 1);
  EXPECT_EQ(r.inflow, -1);
  EXPECT_EQ(s.pressure_fixed(), (std::vector<char>{0, 0, 0, 0, 0, 1}));
}

TEST(PressureLevel, AWeaklyCompressibleFluidIsLeftAlone) {
  TwoParts s;
  EXPECT_EQ(s.anchor(2.2e9).pinned, 0);
  EXPECT_EQ(s.pressure_fixed(), (std::vector<char>(6, 0)));
}

TEST(PressureLevel, APrescribedPressureAnchorsItsPart) {
  TwoParts s;
  s.fixed[3 * 3 + 2] = 1;  // an outlet's particle
  EXPECT_EQ(s.anchor(0.0).pinned, 0);
}

TEST(PressureLevel, AnEnclosedPartAnInflowFeedsIsReportedAndNotPinned) {
  TwoParts s;
  s.inflow[3] = 2;
  s.inflow[4] = 2;
  s.free[4] = 1;    // the inlet's end, marked free surface by the edge along the inlet
  s.fixed[14] = 1;  // and given p = 0 by the Dirichlet condition
  const PressureLevelParts r = s.anchor(0.0);
  EXPECT_EQ(r.inflow, 2);
  EXPECT_EQ(r.pinned, 0);
  EXPECT_EQ(s.fixed[17], 0);
}

}  // namespace
}  // namespace lagfsi::fluid
