#include <lagfsi/assembly.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace lagfsi {

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn, Colouring colouring)
    : m_(npe * dpn),
      npe_(npe),
      dpn_(dpn),
      ne_(static_cast<Index>(conn.size() / npe)),
      colour_(colouring == Colouring::colour) {
  std::vector<Index> all(static_cast<size_t>(ne_));
  for (Index e = 0; e < ne_; ++e) all[static_cast<size_t>(e)] = e;
  build(conn, npe, num_nodes, dpn, all);
}

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn,
                               const std::vector<char>& keep, Colouring colouring)
    : m_(npe * dpn),
      npe_(npe),
      dpn_(dpn),
      ne_(static_cast<Index>(conn.size() / npe)),
      colour_(colouring == Colouring::colour) {
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
  // Each node's incidences, in compressed rows: (k npe + a, then the element's npe nodes), k the element's place
  // among `elements` and a the node's place in it. Everything below then reads them node by node, in order: the
  // only scattered accesses are the writes that lay them out and those of the scatter map.
  const int rec = npe + 1;
  std::vector<int> istart(static_cast<size_t>(num_nodes) + 1, 0);
  for (Index e : elements) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    for (int a = 0; a < npe; ++a) ++istart[static_cast<size_t>(c[a]) + 1];
  }
  for (Index n = 0; n < num_nodes; ++n) istart[n + 1] += istart[n];
  std::vector<Index> inc(static_cast<size_t>(istart[num_nodes]) * rec);
  {
    std::vector<int> fill(istart.begin(), istart.end() - 1);
    for (size_t k = 0; k < elements.size(); ++k) {
      const Index* c = conn.data() + static_cast<size_t>(elements[k]) * npe;
      for (int a = 0; a < npe; ++a) {
        Index* r = inc.data() + static_cast<size_t>(fill[c[a]]++) * rec;
        r[0] = static_cast<Index>(k) * npe + a;
        std::copy(c, c + npe, r + 1);
      }
    }
  }
  // Node adjacency in compressed rows (each node is its own neighbour, also when it is in no element), sorted and
  // without repeats: about one entry a node and one an incidence (a boundary node has one neighbour more).
  std::vector<int> start(static_cast<size_t>(num_nodes) + 1, 0);
  std::vector<Index> adj;
  adj.reserve(static_cast<size_t>(num_nodes) + static_cast<size_t>(istart[num_nodes]) + num_nodes / 8);
  std::vector<Index> row;
  for (Index n = 0; n < num_nodes; ++n) {
    row.assign(1, n);
    for (int p = istart[n]; p < istart[n + 1]; ++p) {
      const Index* r = inc.data() + static_cast<size_t>(p) * rec;
      row.insert(row.end(), r + 1, r + 1 + npe);
    }
    std::sort(row.begin(), row.end());
    adj.insert(adj.end(), row.begin(), std::unique(row.begin(), row.end()));
    start[n + 1] = static_cast<int>(adj.size());
  }
  // The CSC pattern (symmetric: columns = rows), written straight into the matrix.
  const Index nd = num_nodes * dpn;
  size_t nnz = 0;
  for (Index n = 0; n < num_nodes; ++n) nnz += static_cast<size_t>(start[n + 1] - start[n]) * dpn * dpn;
  pattern_.resize(nd, nd);
  pattern_.resizeNonZeros(static_cast<Index>(nnz));
  int* outer = pattern_.outerIndexPtr();
  int* inner = pattern_.innerIndexPtr();
  outer[0] = 0;
  int pos = 0;
  for (Index i = 0; i < num_nodes; ++i)
    for (int c = 0; c < dpn; ++c) {
      for (int k = start[i]; k < start[i + 1]; ++k)
        for (int d = 0; d < dpn; ++d) inner[pos++] = dpn * adj[k] + d;
      outer[dpn * i + c + 1] = pos;
    }
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + nnz, 0.0);

  // Scatter (assembly.hpp), node by node: for each element of node n (its local node a), the base outer[dpn n] +
  // dpn k of each node pair (a, b), k the place of node b among n's neighbours, and the stride dpn (neighbours of n).
  per_element_ = static_cast<size_t>(npe) * npe + (dpn > 1 ? npe : 0);
  scatter_.resize(elements.size() * per_element_);
  const int* op = pattern_.outerIndexPtr();
  for (Index n = 0; n < num_nodes; ++n) {
    const Index* first = adj.data() + start[n];
    const Index* last = adj.data() + start[n + 1];
    for (int p = istart[n]; p < istart[n + 1]; ++p) {
      const Index* r = inc.data() + static_cast<size_t>(p) * rec;
      const int a = r[0] % npe;
      int* sc = scatter_.data() + static_cast<size_t>(r[0] / npe) * per_element_;
      for (int b = 0; b < npe; ++b)
        sc[a * npe + b] = op[dpn * n] + dpn * static_cast<int>(std::lower_bound(first, last, r[1 + b]) - first);
      if (dpn > 1) sc[npe * npe + a] = dpn * static_cast<int>(last - first);
    }
  }
  if (!colour_) return;

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
