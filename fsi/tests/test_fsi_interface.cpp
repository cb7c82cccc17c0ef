// The transfer between a structure's wet boundary nodes and the fluid's ghost particles (fsi::InterfaceMap):
// ghosts reproduce the boundary's shape, forces keep their sum and their work, neighbours are listed.
#include <lagfsi/fsi/dirichlet_neumann.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using lagfsi::Index;
using lagfsi::InterfaceBoundary;
using lagfsi::Vec;
using lagfsi::Vec2;
using lagfsi::fsi::InterfaceMap;

/// A chain of `edges` cubic edges (4 nodes each) along a quarter circle of radius 0.1 (curved edges), or a
/// straight line when `curved` is false. Nodes numbered along the chain, global ids offset by 100.
InterfaceBoundary chain(int edges, bool curved) {
  InterfaceBoundary b;
  const int n = 3 * edges + 1;
  for (int k = 0; k < n; ++k) {
    const double s = double(k) / (n - 1);
    b.nodes.push_back(100 + k);
    b.reference.push_back(curved ? Vec2(0.1 * std::cos(s * M_PI / 2), 0.1 * std::sin(s * M_PI / 2))
                                 : Vec2(0.2 * s, 0.0));
  }
  for (int e = 0; e < edges; ++e) b.edges.push_back({100 + 3 * e, 100 + 3 * e + 1, 100 + 3 * e + 2, 100 + 3 * e + 3});
  return b;
}

Vec positions(const InterfaceBoundary& b) {
  Vec x(2 * b.nodes.size());
  for (size_t k = 0; k < b.nodes.size(); ++k) x.segment<2>(2 * k) = b.reference[k];
  return x;
}

Vec random_vector(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec v(n);
  for (Index i = 0; i < n; ++i) v[i] = u(gen);
  return v;
}

TEST(InterfaceMap, MatchingInterfaceIsOneGhostPerNode) {
  const auto b = chain(3, true);
  const InterfaceMap m(b, 0.0);
  ASSERT_EQ(m.num_ghosts(), static_cast<Index>(b.nodes.size()));
  const Vec x = positions(b);
  EXPECT_LT((m.to_ghosts(x) - x).norm(), 1e-15);
  const Vec f = random_vector(x.size(), 1);
  EXPECT_LT((m.to_nodes(f) - f).norm(), 1e-15);
  EXPECT_EQ(m.adjacent().size(), b.nodes.size() - 1);  // an open chain
}

TEST(InterfaceMap, NonMatchingGhostsFollowTheEdgesAtTheSpacing) {
  const auto b = chain(4, false);   // 0.2 m in 4 edges of 0.05 m
  const InterfaceMap m(b, 0.0125);  // 4 segments per edge, vertex ghosts shared
  ASSERT_EQ(m.num_ghosts(), 4 * 4 + 1);
  EXPECT_EQ(m.adjacent().size(), 16u);
  // Ghosts at the spacing along the line, in the reference and through to_ghosts.
  const Vec xg = m.to_ghosts(positions(b));
  for (Index g = 0; g < m.num_ghosts(); ++g) {
    EXPECT_NEAR(xg[2 * g + 1], 0.0, 1e-15);
    EXPECT_NEAR(xg[2 * g], m.reference()[g].x(), 1e-14);
  }
  for (const auto& [a, c] : m.adjacent()) EXPECT_NEAR(std::abs(xg[2 * a] - xg[2 * c]), 0.0125, 1e-12);
}

TEST(InterfaceMap, ForcesKeepTheirSumAndTheirWork) {
  // Curved cubic edges, a spacing that does not divide them: the total force and the work of any ghost
  // forces on any nodal motion are the same on both sides of the transfer.
  const auto b = chain(3, true);
  const InterfaceMap m(b, 0.007);
  ASSERT_GT(m.num_ghosts(), static_cast<Index>(b.nodes.size()));
  const Vec F = random_vector(2 * m.num_ghosts(), 2);
  const Vec f = m.to_nodes(F);
  Vec2 sum_g = Vec2::Zero(), sum_n = Vec2::Zero();
  for (Index g = 0; g < m.num_ghosts(); ++g) sum_g += F.segment<2>(2 * g);
  for (size_t k = 0; k < b.nodes.size(); ++k) sum_n += f.segment<2>(2 * k);
  EXPECT_LT((sum_g - sum_n).norm(), 1e-12 * F.norm());
  const Vec u = random_vector(2 * static_cast<Index>(b.nodes.size()), 3);
  EXPECT_NEAR(f.dot(u), F.dot(m.to_ghosts(u)), 1e-12 * F.norm() * u.norm());
  // A rigid translation of the nodes moves every ghost by the same amount (partition of unity).
  Vec t(u.size());
  for (Index k = 0; k < t.size() / 2; ++k) t.segment<2>(2 * k) = Vec2(0.3, -0.2);
  const Vec tg = m.to_ghosts(t);
  for (Index g = 0; g < m.num_ghosts(); ++g) EXPECT_LT((tg.segment<2>(2 * g) - Vec2(0.3, -0.2)).norm(), 1e-13);
  // The ghosts lie on the cubic edges: within the cubic's error of the circle (radius 0.1).
  const Vec xg = m.to_ghosts(positions(b));
  for (Index g = 0; g < m.num_ghosts(); ++g) EXPECT_NEAR(xg.segment<2>(2 * g).norm(), 0.1, 1e-5);
}

TEST(InterfaceMap, EdgeNodesMustBeInterfaceNodes) {
  auto b = chain(1, false);
  b.edges[0][2] = 999;
  EXPECT_THROW(InterfaceMap(b, 0.01), std::invalid_argument);
}

}  // namespace
