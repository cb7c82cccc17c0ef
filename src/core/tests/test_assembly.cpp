// The sparse pattern of a mesh and its scatter map (assembly.hpp): the whole mesh's, and that of a subset of its
// elements (what an MPI process that fills its own rows assembles), which must put each kept element's entries at
// the same (row, column) pairs as the whole pattern does.
#include <gtest/gtest.h>

#include <lagfsi/assembly.hpp>

#include <Eigen/Dense>

#include <map>
#include <utility>
#include <vector>

namespace {

using lagfsi::ElementPattern;
using lagfsi::Index;

/// (row, column) of every value index of a pattern.
std::vector<std::pair<int, int>> positions(const ElementPattern& p) {
  const auto& A = p.pattern();
  std::vector<std::pair<int, int>> at(static_cast<size_t>(A.nonZeros()));
  for (int col = 0; col < A.outerSize(); ++col)
    for (int k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k)
      at[static_cast<size_t>(k)] = {A.innerIndexPtr()[k], col};
  return at;
}

// A strip of four triangles over six nodes: 0-1-2, 1-3-2, 2-3-4, 3-5-4; two unknowns per node.
const std::vector<Index> kConn{0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4};

TEST(ElementPattern, AKeptElementScattersToTheSameEntriesAsInTheWholePattern) {
  const ElementPattern whole(kConn, 3, 6, 2);
  const ElementPattern part(kConn, 3, 6, 2, {1, 0, 0, 1});
  const auto w = positions(whole), p = positions(part);
  for (Index e : {0, 3})
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        EXPECT_EQ(w[static_cast<size_t>(whole.position(e, i, j))], p[static_cast<size_t>(part.position(e, i, j))])
            << "element " << e << ", entry " << i << ", " << j;
  // Elements 0 and 3 share no node: their blocks (9 node pairs each, 4 values a pair) and nothing else.
  EXPECT_EQ(part.pattern().nonZeros(), 2 * 9 * 4);
  EXPECT_EQ(whole.pattern().nonZeros(), (6 + 2 * 9) * 4);  // 6 diagonal and 9 edge pairs (both ways)
  std::vector<Index> colored;
  for (const auto& c : part.colors()) colored.insert(colored.end(), c.begin(), c.end());
  EXPECT_EQ(colored.size(), 2u) << "only the kept elements are coloured";
}

TEST(ElementPattern, EachLocalEntryIsAddedAtItsOwnRowAndColumn) {
  for (int dpn : {1, 2, 3}) {
    const ElementPattern whole(kConn, 3, 6, dpn);
    const auto at = positions(whole);
    const int m = 3 * dpn;
    for (Index e = 0; e < 4; ++e) {
      const Index* c = kConn.data() + 3 * e;
      // A local matrix whose entry (i, j) is 1 + i + m j, added into zeros: each value lands at its dofs.
      Eigen::MatrixXd K(m, m);
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) K(i, j) = 1 + i + m * j;
      std::vector<double> v(static_cast<size_t>(whole.pattern().nonZeros()), 0.0);
      whole.add(e, K, v.data());
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const int k = whole.position(e, i, j);
          EXPECT_EQ(at[static_cast<size_t>(k)], std::make_pair(dpn * c[i / dpn] + i % dpn, dpn * c[j / dpn] + j % dpn))
              << "dofs per node " << dpn << ", element " << e << ", entry " << i << ", " << j;
          EXPECT_EQ(v[static_cast<size_t>(k)], K(i, j));
        }
      if (dpn == 1) {
        for (int k = 0; k < 9; ++k) EXPECT_EQ(whole.scatter(e)[k], whole.position(e, k % 3, k / 3));
      }
      // A node-by-node matrix on every component: entry (a, b) on the dofs (dpn a + d, dpn b + d).
      Eigen::Matrix3d M;
      M << 1, 2, 3, 4, 5, 6, 7, 8, 9;
      std::fill(v.begin(), v.end(), 0.0);
      whole.add_per_component(e, M, v.data());
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a)
          for (int d = 0; d < dpn; ++d)
            EXPECT_EQ(v[static_cast<size_t>(whole.position(e, dpn * a + d, dpn * b + d))], M(a, b));
    }
  }
}

TEST(ElementPattern, WithoutColoursThePatternAndTheScatterMapAreTheSame) {
  for (int dpn : {1, 3}) {
    const ElementPattern coloured(kConn, 3, 6, dpn, {1, 1, 0, 1});
    const ElementPattern plain(kConn, 3, 6, dpn, {1, 1, 0, 1}, ElementPattern::Colouring::none);
    EXPECT_TRUE(plain.colors().empty());
    size_t in_colours = 0;
    for (const auto& c : coloured.colors()) in_colours += c.size();
    EXPECT_EQ(in_colours, 3u);
    EXPECT_EQ(positions(plain), positions(coloured));
    for (Index e : {0, 1, 3})
      for (int j = 0; j < 3 * dpn; ++j)
        for (int i = 0; i < 3 * dpn; ++i) EXPECT_EQ(plain.position(e, i, j), coloured.position(e, i, j));
  }
}

TEST(ElementPattern, ANodeOfNoKeptElementKeepsItsDiagonal) {
  const ElementPattern part(kConn, 3, 6, 1, {1, 0, 0, 0});
  const auto p = positions(part);
  std::map<std::pair<int, int>, int> count;
  for (const auto& rc : p) ++count[rc];
  for (int n = 3; n < 6; ++n) EXPECT_EQ(count[std::make_pair(n, n)], 1) << "node " << n;
  EXPECT_EQ(part.pattern().nonZeros(), 9 + 3);
}

}  // namespace
