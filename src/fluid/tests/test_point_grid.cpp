// The fluid's proximity grid (src/fluid/point_grid.hpp, white box): PointGrid::find must return what a search
// of every point added so far returns, the largest id within r of the query, for points spread over cells of
// either sign, added and queried in turn (as the particle management does), through the table's growth (the
// grid is sized for 16 points and gets thousands), for points far from the origin (clamped cells) and for a
// query radius equal to the cell size.
#include "point_grid.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::fluid::PointGrid;

Index brute_force(const std::vector<Vec2>& pts, Index added, const Vec2& p, double r) {
  Index found = -1;
  for (Index j = 0; j < added; ++j)
    if ((pts[static_cast<size_t>(j)] - p).norm() < r) found = std::max(found, j);
  return found;
}

TEST(PointGrid, FindsTheLastAddedPointWithinTheRadiusAsASearchOfAllPointsDoes) {
  for (const double cell : {0.05, 0.3}) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    PointGrid grid(cell);  // no size hint: the table grows from 16 slots
    std::vector<Vec2> pts;
    int hits = 0;
    for (int k = 0; k < 4000; ++k) {
      const Vec2 p(u(rng), u(rng));
      for (const double r : {0.3 * cell, cell}) {
        const Index expected = brute_force(pts, static_cast<Index>(pts.size()), p, r);
        ASSERT_EQ(grid.find(p, r, pts), expected) << "cell " << cell << ", point " << k << ", r " << r;
        hits += expected >= 0;
      }
      grid.add(p, static_cast<Index>(pts.size()));
      pts.push_back(p);
    }
    EXPECT_GT(hits, 100) << "the test must find points, not only miss them";
  }
}

TEST(PointGrid, SeveralPointsInOneCellAndPointsFarFromTheOrigin) {
  PointGrid grid(1.0, 4);
  const std::vector<Vec2> pts = {{0.1, 0.1}, {0.2, 0.1}, {0.9, 0.9}, {1e300, -1e300}, {1e300, -1e300}, {-0.03, 0.1}};
  for (Index i = 0; i < static_cast<Index>(pts.size()); ++i) grid.add(pts[static_cast<size_t>(i)], i);
  EXPECT_EQ(grid.find({0.15, 0.1}, 0.2, pts), 5);   // 0, 1 and 5 (across the cell boundary) are within 0.2
  EXPECT_EQ(grid.find({0.15, 0.1}, 0.06, pts), 1);  // 0 and 1
  EXPECT_EQ(grid.find({0.95, 0.95}, 0.1, pts), 2);
  EXPECT_EQ(grid.find({5.0, 5.0}, 1.0, pts), -1);
  EXPECT_EQ(grid.find({1e300, -1e300}, 1.0, pts), 4);  // the clamped cell: the distance test decides
}

}  // namespace
