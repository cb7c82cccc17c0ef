#include <lagfsi/assembly.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace lagfsi {

ElementPattern::ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn)
    : m_(npe * dpn), ne_(static_cast<Index>(conn.size() / npe)) {
  // Node adjacency (each node is its own neighbour, also when it is in no element).
  std::vector<std::vector<Index>> adj(num_nodes);
  for (Index n = 0; n < num_nodes; ++n) adj[n].push_back(n);
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b) adj[c[a]].push_back(c[b]);
  }
  const Index nd = num_nodes * dpn;
  std::vector<int> outer(nd + 1, 0), inner;
  for (auto& v : adj) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  size_t nnz = 0;
  for (const auto& v : adj) nnz += v.size() * dpn * dpn;
  inner.reserve(nnz);
  for (Index i = 0; i < num_nodes; ++i)
    for (int c = 0; c < dpn; ++c) {
      outer[dpn * i + c + 1] = outer[dpn * i + c] + static_cast<int>(dpn * adj[i].size());
      for (Index j : adj[i])
        for (int d = 0; d < dpn; ++d) inner.push_back(dpn * j + d);
    }
  std::vector<double> values(inner.size(), 0.0);
  pattern_ = Eigen::Map<const SparseMatrix>(nd, nd, static_cast<int>(inner.size()), outer.data(), inner.data(),
                                            values.data());
  pattern_.makeCompressed();

  scatter_.resize(static_cast<size_t>(ne_) * m_ * m_);
  const int* op = pattern_.outerIndexPtr();
  const int* ip = pattern_.innerIndexPtr();
  for (Index e = 0; e < ne_; ++e) {
    const Index* c = conn.data() + static_cast<size_t>(e) * npe;
    int* sc = scatter_.data() + static_cast<size_t>(e) * m_ * m_;
    for (int j = 0; j < m_; ++j) {
      const int gj = dpn * c[j / dpn] + j % dpn;
      for (int i = 0; i < m_; ++i) {
        const int gi = dpn * c[i / dpn] + i % dpn;
        sc[j * m_ + i] = static_cast<int>(std::lower_bound(ip + op[gj], ip + op[gj + 1], gi) - ip);
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
