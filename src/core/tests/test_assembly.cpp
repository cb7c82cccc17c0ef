// The sparse pattern of a mesh and its scatter map (assembly.hpp): the whole mesh's, and that of a subset of its
// elements (what an MPI process that fills its own rows assembles), which must put each kept element's entries at
// the same (row, column) pairs as the whole pattern does.
#include <gtest/gtest.h>

#include <lagfsi/assembly.hpp>

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
    for (int k = 0; k < 36; ++k)
      EXPECT_EQ(w[static_cast<size_t>(whole.scatter(e)[k])], p[static_cast<size_t>(part.scatter(e)[k])])
          << "element " << e << ", entry " << k;
  // Elements 0 and 3 share no node: their blocks (9 node pairs each, 4 values a pair) and nothing else.
  EXPECT_EQ(part.pattern().nonZeros(), 2 * 9 * 4);
  EXPECT_EQ(whole.pattern().nonZeros(), (6 + 2 * 9) * 4);  // 6 diagonal and 9 edge pairs (both ways)
  std::vector<Index> colored;
  for (const auto& c : part.colors()) colored.insert(colored.end(), c.begin(), c.end());
  EXPECT_EQ(colored.size(), 2u) << "only the kept elements are coloured";
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
