// The mesh's boundary edges (src/fluid/fluid_mesh.hpp, white box): a square of two triangles has four boundary
// edges; asked again after its triangles change (a third triangle glued on, one removed, the particles renumbered)
// the answer is the new mesh's, not the one kept from before.
#include <gtest/gtest.h>

#include "fluid_mesh.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace lagfsi::fluid {
namespace {

// The boundary as directed particle pairs, sorted.
std::vector<std::pair<Index, Index>> directed(const FluidMesh& m) {
  std::vector<std::pair<Index, Index>> out;
  for (const auto& [e, k] : m.boundary_edges()) out.emplace_back(m.tri[e][k], m.tri[e][(k + 1) % 3]);
  std::sort(out.begin(), out.end());
  return out;
}

using Edges = std::vector<std::pair<Index, Index>>;

TEST(FluidMesh, TheBoundaryEdgesFollowTheTrianglesWhenTheyChange) {
  FluidMesh m;
  EXPECT_TRUE(m.boundary_edges().empty());
  m.tri = {{0, 1, 2}, {0, 2, 3}};  // the unit square 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1)
  EXPECT_EQ(directed(m), (Edges{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
  EXPECT_EQ(directed(m), (Edges{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));  // asked twice, the same
  m.tri.push_back({1, 4, 2});  // a triangle glued on the right: edge 1-2 is inside now
  EXPECT_EQ(directed(m), (Edges{{0, 1}, {1, 4}, {2, 3}, {3, 0}, {4, 2}}));
  m.tri.erase(m.tri.begin());  // the first triangle gone: 0-2 is on the boundary, 1-2 again
  EXPECT_EQ(directed(m), (Edges{{0, 2}, {1, 4}, {2, 1}, {2, 3}, {3, 0}, {4, 2}}));
  m.tri = {{1, 0, 3}, {1, 3, 2}};  // the square again, renumbered in place (the same size)
  EXPECT_EQ(directed(m), (Edges{{0, 3}, {1, 0}, {2, 1}, {3, 2}}));
  m.tri.clear();
  EXPECT_TRUE(m.boundary_edges().empty());
}

}  // namespace
}  // namespace lagfsi::fluid
