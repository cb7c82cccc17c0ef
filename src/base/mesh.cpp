#include <lagfsi/mesh.hpp>

#include <algorithm>
#include <map>
#include <utility>

namespace lagfsi {

namespace {
// Local node indices of the order+1 nodes of local edge k, from its first vertex to its second.
std::vector<int> local_edge_nodes(int order, int k) {
  const int v0 = k, v1 = (k + 1) % 3;
  std::vector<int> out{v0};
  for (int i = 0; i < order - 1; ++i) out.push_back(3 + k * (order - 1) + i);
  out.push_back(v1);
  return out;
}
}  // namespace

std::vector<BoundaryEdge> boundary_edges(const TriMesh& mesh) {
  // Count each vertex pair; an edge used once is on the boundary.
  std::map<std::pair<Index, Index>, std::pair<int, std::pair<Index, int>>> count;
  const Index ne = mesh.num_elements();
  for (Index e = 0; e < ne; ++e) {
    const Index* c = mesh.element(e);
    for (int k = 0; k < 3; ++k) {
      Index a = c[k], b = c[(k + 1) % 3];
      auto key = std::minmax(a, b);
      auto& entry = count[{key.first, key.second}];
      entry.first += 1;
      entry.second = {e, k};
    }
  }
  std::vector<BoundaryEdge> out;
  for (const auto& [key, entry] : count) {
    if (entry.first != 1) continue;
    const auto [e, k] = entry.second;
    BoundaryEdge be{e, k, {}};
    const Index* c = mesh.element(e);
    for (int l : local_edge_nodes(mesh.order, k)) be.nodes.push_back(c[l]);
    out.push_back(std::move(be));
  }
  return out;
}

}  // namespace lagfsi
