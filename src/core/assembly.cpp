#include <lagfsi/assembly.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace lagfsi {

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn)
    : m_(npe * dpn), ne_(static_cast<Index>(conn.size() / npe)) {
  // Node adjacency in compressed rows (each node is its own neighbour, also when it is in no element):
  // count, fill, then sort and deduplicate each row in place.
  std::vector<int> start(num_nodes + 1, 0);
  for (Index n = 0; n < num_nodes; ++n) start[n + 1] = 1;
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    for (int a = 0; a < npe; ++a) start[c[a] + 1] += npe;
  }
  for (Index n = 0; n < num_nodes; ++n) start[n + 1] += start[n];
  std::vector<Index> adj(start[num_nodes]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Index n = 0; n < num_nodes; ++n) adj[fill[n]++] = n;
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b) adj[fill[c[a]]++] = c[b];
  }
  std::vector<int> count(num_nodes);
  for (Index n = 0; n < num_nodes; ++n) {
    Index* first = adj.data() + start[n];
    Index* last = adj.data() + start[n + 1];
    std::sort(first, last);
    count[n] = static_cast<int>(std::unique(first, last) - first);
  }
  // The CSC pattern (symmetric: columns = rows), written straight into the matrix.
  const Index nd = num_nodes * dpn;
  size_t nnz = 0;
  for (Index n = 0; n < num_nodes; ++n) nnz += static_cast<size_t>(count[n]) * dpn * dpn;
  pattern_.resize(nd, nd);
  pattern_.resizeNonZeros(static_cast<Index>(nnz));
  int* outer = pattern_.outerIndexPtr();
  int* inner = pattern_.innerIndexPtr();
  outer[0] = 0;
  int pos = 0;
  for (Index i = 0; i < num_nodes; ++i)
    for (int c = 0; c < dpn; ++c) {
      for (int k = 0; k < count[i]; ++k)
        for (int d = 0; d < dpn; ++d) inner[pos++] = dpn * adj[start[i] + k] + d;
      outer[dpn * i + c + 1] = pos;
    }
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + nnz, 0.0);

  // Scatter: column dpn n + c holds, for each neighbour of node n in order, its dpn rows; so the entry of row
  // dpn m + d is at outer[dpn n + c] + dpn k + d, k the place of m among n's neighbours (one search per node
  // pair, not per dof pair).
  scatter_.resize(static_cast<size_t>(ne_) * m_ * m_);
  const int* op = pattern_.outerIndexPtr();
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    int* sc = scatter_.data() + static_cast<size_t>(e) * m_ * m_;
    for (int a = 0; a < npe; ++a) {
      const Index* row = adj.data() + start[c[a]];
      for (int b = 0; b < npe; ++b) {
        const int k = static_cast<int>(std::lower_bound(row, row + count[c[a]], c[b]) - row);
        for (int cj = 0; cj < dpn; ++cj) {
          const int base = op[dpn * c[a] + cj] + dpn * k;
          for (int ci = 0; ci < dpn; ++ci) sc[(a * dpn + cj) * m_ + b * dpn + ci] = base + ci;
        }
      }
    }
  }

  // Greedy colouring with a bit mask of the colours used at each node.
  std::vector<std::uint64_t> used(num_nodes, 0);
  std::vector<int> color(ne_);
  int ncolors = 0;
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    std::uint64_t forbidden = 0;
    for (int a = 0; a < npe; ++a) forbidden |= used[c[a]];
    int k = 0;
    while (k < 64 && ((forbidden >> k) & 1u)) ++k;
    if (k == 64) throw std::runtime_error("element colouring needs more than 64 colours (degenerate mesh?)");
    color[e] = k;
    ncolors = std::max(ncolors, k + 1);
    for (int a = 0; a < npe; ++a) used[c[a]] |= (std::uint64_t(1) << k);
  }
  colors_.assign(ncolors, {});
  for (Index e = 0; e < ne_; ++e) colors_[color[e]].push_back(e);
}

}  // namespace lagfsi
