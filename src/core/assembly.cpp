#include <lagfsi/assembly.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace lagfsi {

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn)
    : m_(npe * dpn), npe_(npe), dpn_(dpn), ne_(static_cast<Index>(conn.size() / npe)) {
  std::vector<Index> all(static_cast<size_t>(ne_));
  for (Index e = 0; e < ne_; ++e) all[static_cast<size_t>(e)] = e;
  build(conn, npe, num_nodes, dpn, all);
}

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn,
                               const std::vector<char>& keep)
    : m_(npe * dpn), npe_(npe), dpn_(dpn), ne_(static_cast<Index>(conn.size() / npe)) {
  if (keep.size() != static_cast<size_t>(ne_)) throw std::invalid_argument("ElementPattern: one keep flag per element");
  std::vector<Index> kept;
  slot_.assign(static_cast<size_t>(ne_), -1);
  for (Index e = 0; e < ne_; ++e)
    if (keep[static_cast<size_t>(e)]) {
      slot_[static_cast<size_t>(e)] = static_cast<Index>(kept.size());
      kept.push_back(e);
    }
  build(conn, npe, num_nodes, dpn, kept);
}

void ElementPattern::build(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn,
                           const std::vector<Index>& elements) {
  // Node adjacency in compressed rows (each node is its own neighbour, also when it is in no element):
  // count, fill, then sort and deduplicate each row in place.
  std::vector<int> start(num_nodes + 1, 0);
  for (Index n = 0; n < num_nodes; ++n) start[n + 1] = 1;
  for (Index e : elements) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    for (int a = 0; a < npe; ++a) start[c[a] + 1] += npe;
  }
  for (Index n = 0; n < num_nodes; ++n) start[n + 1] += start[n];
  std::vector<Index> adj(start[num_nodes]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Index n = 0; n < num_nodes; ++n) adj[fill[n]++] = n;
  for (Index e : elements) {
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

  // Scatter (assembly.hpp): per node pair (a, b) the base outer[dpn c_a] + dpn k, k the place of c_b among c_a's
  // neighbours, and per node the stride dpn (neighbours of c_a) between the columns of c_a's unknowns.
  per_element_ = static_cast<size_t>(npe) * npe + (dpn > 1 ? npe : 0);
  scatter_.resize(elements.size() * per_element_);
  const int* op = pattern_.outerIndexPtr();
  for (size_t k = 0; k < elements.size(); ++k) {
    const Index* c = conn.data() + static_cast<size_t>(elements[k]) * npe;
    int* sc = scatter_.data() + k * per_element_;
    for (int a = 0; a < npe; ++a) {
      const Index* row = adj.data() + start[c[a]];
      for (int b = 0; b < npe; ++b) {
        const int place = static_cast<int>(std::lower_bound(row, row + count[c[a]], c[b]) - row);
        sc[a * npe + b] = op[dpn * c[a]] + dpn * place;
      }
      if (dpn > 1) sc[npe * npe + a] = dpn * count[c[a]];
    }
  }

  // Greedy colouring with a bit mask of the colours used at each node.
  std::vector<std::uint64_t> used(num_nodes, 0);
  std::vector<int> color(elements.size());
  int ncolors = 0;
  for (size_t kk = 0; kk < elements.size(); ++kk) {
    const Index* c = conn.data() + static_cast<size_t>(elements[kk]) * npe;
    std::uint64_t forbidden = 0;
    for (int a = 0; a < npe; ++a) forbidden |= used[c[a]];
    int k = 0;
    while (k < 64 && ((forbidden >> k) & 1u)) ++k;
    if (k == 64) throw std::runtime_error("element colouring needs more than 64 colours (degenerate mesh?)");
    color[kk] = k;
    ncolors = std::max(ncolors, k + 1);
    for (int a = 0; a < npe; ++a) used[c[a]] |= (std::uint64_t(1) << k);
  }
  colors_.assign(ncolors, {});
  for (size_t k = 0; k < elements.size(); ++k) colors_[color[k]].push_back(elements[k]);
}

}  // namespace lagfsi
