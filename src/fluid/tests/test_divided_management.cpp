// The particle management's searches divided among MPI processes (divided_management.cpp, a white-box test of the
// private src/fluid/remesh_pipeline.hpp), run by CTest under mpirun with 1, 2 and 3 processes. Each process searches
// for the particles of its part of space (a recursive coordinate bisection), and every process then takes all the
// candidates in particle order: the merges are those of one process over all the particles, whatever the cut.
//  - Two rows of drops 0.2 h apart (within remove_close_fraction h = 0.3 h of their neighbours, not of the next
//    ones), the second shifted by one spacing: taken in particle order, each row merges in pairs from its first drop
//    on. The parts are cut across the rows, so wherever the cut falls, it splits a pair of one row; a process that
//    took only its own candidates would pair the drops on its side of the cut from the cut on.
//  - Three particles put on one wall corner in one step become one, as on one process: the merges onto walls.
#include <gtest/gtest.h>

#include <lagfsi/mpi_run.hpp>

#include "remesh_scene.hpp"

#include <algorithm>
#include <vector>

namespace lagfsi::fluid {
namespace {

using fluid_test::kH;
using Scene = fluid_test::RemeshScene;

TEST(DividedManagement, RowsOfDropsMergeInPairsFromTheirFirstDropWhereverTheProcessesAreCut) {
  mpi_run::start();
  constexpr int kDrops = 41;
  constexpr double d = 0.2 * kH;
  std::vector<Vec2> pts;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < kDrops; ++k) pts.emplace_back((k + row) * d, 5.0 * kH * row);
  Scene s(pts, {});
  ASSERT_NO_THROW(s.remesh.remesh_step(0.001, s.volume, s.energy));
  // Each row: its pairs (2k, 2k + 1) at their centres, and its last drop where it was.
  std::vector<Vec2> expected;
  for (int row = 0; row < 2; ++row) {
    for (int k = 0; k + 1 < kDrops; k += 2) expected.emplace_back((k + 0.5 + row) * d, 5.0 * kH * row);
    expected.emplace_back((kDrops - 1 + row) * d, 5.0 * kH * row);
  }
  ASSERT_EQ(s.cloud.n(), static_cast<Index>(expected.size())) << "on " << mpi_run::size() << " processes";
  std::vector<Vec2> got;
  for (Index i = 0; i < s.cloud.n(); ++i) got.push_back(s.cloud.pos(i));
  const auto by_x = [](const Vec2& a, const Vec2& b) { return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x()); };
  std::sort(got.begin(), got.end(), by_x);
  std::sort(expected.begin(), expected.end(), by_x);
  for (size_t k = 0; k < got.size(); ++k)
    EXPECT_LT((got[k] - expected[k]).norm(), 1e-12 * kH)
        << "particle " << k << " on " << mpi_run::size() << " processes";
  EXPECT_EQ(s.remesh.summary()["pairs_merged_meeting"], kDrops - 1);
}

TEST(DividedManagement, ThreeParticlesPutOnOneCornerBecomeOneOnEveryProcess) {
  mpi_run::start();
  // A square of side h in the corner of a floor and a wall (test_particle_management.cpp): 0, 1 and 2 put on the
  // corner at the end of the step. The three coincide, so a cut may separate them.
  Scene s({{0, 0}, {0, 0}, {0, 0}, {kH, 0}, {kH, kH}, {0, kH}}, {{0, 3, 4}, {1, 4, 5}});
  s.cloud.owed() << 1e-7, 2e-7, 3e-7, 0, 0, 0;
  const double before = s.water();
  const std::vector<char> on_wall = {2, 2, 2, 1, 0, 1};
  ASSERT_NO_THROW(s.remesh.remesh_step(0.001, s.volume, s.energy, on_wall));
  ASSERT_EQ(s.cloud.n(), 4) << "one particle is left on the corner";
  EXPECT_EQ(s.cloud.pos(0), Vec2(0, 0));
  EXPECT_NEAR(s.water(), before, 1e-18) << "what the three were owed is the survivor's";
}

}  // namespace
}  // namespace lagfsi::fluid
