// Unit tests of the space partition and the parts' shares of the Delaunay triangulation (meshing/partition.hpp):
// every point in one part and the parts in proportion; the shares of 2, 3 and 5 parts together are the whole cloud's
// triangles with a circumradius within the halo, each once, for random points, a square lattice (every square's four
// points on one circle) and a jittered lattice with a hole; the ghosts are a layer, not the cloud.
#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::meshing::SpacePartition;
using Triangle = std::array<Index, 3>;

Triangle sorted(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::vector<Vec2> random_points(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) p.emplace_back(2.0 * u(g), u(g));
  return p;
}

/// An n x m lattice of spacing h, jittered by `jitter` h, without the points in the disc (c, r).
std::vector<Vec2> lattice(int n, int m, double h, double jitter, Vec2 c = Vec2(-1, -1), double r = 0) {
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec2> p;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 x(i * h + jitter * h * u(g), j * h + jitter * h * u(g));
      if ((x - c).norm() >= r) p.push_back(x);
    }
  return p;
}

/// The shares of `parts` parts, together, against the whole triangulation's triangles with R <= halo.
void expect_shares_make_the_whole(const std::vector<Vec2>& pts, int parts, double halo) {
  std::set<Triangle> whole;
  for (const Triangle& t : lagfsi::meshing::delaunay_triangles(pts))
    if (lagfsi::meshing::circumcircle(pts, t).second <= halo) whole.insert(sorted(t));
  const SpacePartition partition(pts, parts);
  std::map<Triangle, int> seen;
  Index ghosts = 0;
  for (int k = 0; k < parts; ++k) {
    Index g = 0;
    for (const Triangle& t : lagfsi::meshing::part_delaunay(pts, partition, k, halo, &g)) ++seen[sorted(t)];
    ghosts += g;
  }
  std::size_t missing = 0, extra = 0, twice = 0;
  for (const Triangle& t : whole) missing += seen.count(t) == 0;
  for (const auto& [t, n] : seen) {
    extra += whole.count(t) == 0;
    twice += n > 1;
  }
  EXPECT_EQ(missing, 0u) << parts << " parts";
  EXPECT_EQ(extra, 0u) << parts << " parts";
  EXPECT_EQ(twice, 0u) << parts << " parts";
  EXPECT_EQ(seen.size(), whole.size());
  EXPECT_LT(ghosts, static_cast<Index>(pts.size()) / 2) << "the ghosts are a layer along the cuts";
}

TEST(SpacePartition, EveryPointIsInOnePartAndThePartsAreInProportion) {
  const std::vector<Vec2> pts = random_points(1000, 3);
  for (int parts : {1, 2, 3, 5, 8}) {
    const SpacePartition p(pts, parts);
    ASSERT_EQ(p.parts(), parts);
    std::vector<int> count(static_cast<size_t>(parts), 0);
    for (size_t i = 0; i < pts.size(); ++i) {
      const int k = p.owner()[i];
      ASSERT_GE(k, 0);
      ASSERT_LT(k, parts);
      EXPECT_EQ(p.part_of(pts[i]), k) << "point " << i;
      ++count[static_cast<size_t>(k)];
    }
    const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
    EXPECT_LE(*hi - *lo, 2) << parts << " parts";
  }
  EXPECT_THROW(SpacePartition(pts, 0), std::invalid_argument);
}

TEST(PartDelaunay, TheSharesOfRandomPointsAreTheWholeTriangulation) {
  const std::vector<Vec2> pts = random_points(2000, 11);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 0.1);
}

TEST(PartDelaunay, TheSharesOfALatticeCutItsSquaresAsTheWholeDoes) {
  const std::vector<Vec2> pts = lattice(40, 25, 0.02, 0.0);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 1.2 * 0.02);
}

TEST(PartDelaunay, TheSharesOfAJitteredLatticeWithAHoleAreTheWholeTriangulation) {
  const std::vector<Vec2> pts = lattice(60, 30, 0.01, 0.2, Vec2(0.3, 0.15), 0.08);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 2.5 * 0.01);
}

}  // namespace
