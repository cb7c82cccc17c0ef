// The step's mesh of the fluid particles (fluid_mesh.hpp): connectivity, area and neighbourhood queries.
#include "fluid_mesh.hpp"

#include <algorithm>
#include <array>

namespace lagfsi::fluid {

void FluidMesh::flatten() {
  conn.resize(3 * tri.size());
  for (size_t e = 0; e < tri.size(); ++e)
    for (int k = 0; k < 3; ++k) conn[3 * e + k] = tri[e][k];
}

double FluidMesh::area(const Vec& x) const {
  double a = 0;
  for (Index e = 0; e < num_elements(); ++e) a += element_area(x, e);
  return a;
}

std::vector<double> FluidMesh::nodal_areas(const Vec& x, Index np) const {
  std::vector<double> a(static_cast<size_t>(np), 0.0);
  for (Index e = 0; e < num_elements(); ++e) {
    const double third = element_area(x, e) / 3.0;
    for (Index i : tri[e]) a[static_cast<size_t>(i)] += third;
  }
  return a;
}

std::vector<char> FluidMesh::in_element_with(Index np, const std::function<bool(Index)>& pred) const {
  std::vector<char> flag(static_cast<size_t>(np), 0);
  for (const auto& t : tri)
    if (pred(t[0]) || pred(t[1]) || pred(t[2]))
      for (Index i : t) flag[i] = 1;
  return flag;
}

std::vector<char> FluidMesh::beside_interior_fluid(const std::vector<ParticleKind>& kind) const {
  return in_element_with(static_cast<Index>(kind.size()),
                         [&](Index i) { return kind[i] == ParticleKind::Fluid && !free[i]; });
}

const std::vector<std::pair<Index, int>>& FluidMesh::boundary_edges() const {
  if (boundary_of_ != tri) {
    boundary_ = find_boundary_edges();
    boundary_of_ = tri;
  }
  return boundary_;
}

std::vector<std::pair<Index, int>> FluidMesh::find_boundary_edges() const {
  // The edges bucketed by their smaller particle (a counting sort), each bucket (a few edges) sorted by the
  // larger one: an edge found once is on the boundary. In the order of (smaller, larger) particle.
  const Index ne = num_elements();
  Index np = 0;
  for (const auto& t : tri) np = std::max({np, t[0] + 1, t[1] + 1, t[2] + 1});
  std::vector<int> start(static_cast<size_t>(np) + 1, 0);
  for (const auto& t : tri)
    for (int k = 0; k < 3; ++k) ++start[static_cast<size_t>(std::min(t[k], t[(k + 1) % 3])) + 1];
  for (Index i = 0; i < np; ++i) start[i + 1] += start[i];
  std::vector<std::pair<Index, Index>> edges(3 * static_cast<size_t>(ne));  // (larger particle, 3 e + k)
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Index e = 0; e < ne; ++e)
    for (int k = 0; k < 3; ++k) {
      const Index i = tri[e][k], j = tri[e][(k + 1) % 3];
      edges[static_cast<size_t>(fill[std::min(i, j)]++)] = {std::max(i, j), 3 * e + k};
    }
  std::vector<std::pair<Index, int>> boundary;
  for (Index i = 0; i < np; ++i) {
    const auto first = edges.begin() + start[i], last = edges.begin() + start[i + 1];
    std::sort(first, last);
    for (auto q = first; q != last;) {
      auto r = q + 1;
      while (r != last && r->first == q->first) ++r;
      if (r == q + 1) boundary.emplace_back(q->second / 3, static_cast<int>(q->second % 3));
      q = r;
    }
  }
  return boundary;
}

std::vector<unsigned char> FluidMesh::free_surface_edges(const std::vector<ParticleKind>& kind) const {
  std::vector<unsigned char> mask(tri.size(), 0);
  const auto surface = [&](Index i) { return free[i] && kind[i] == ParticleKind::Fluid; };
  for (const auto& [e, k] : boundary_edges())
    if (surface(tri[e][k]) && surface(tri[e][(k + 1) % 3])) mask[e] |= static_cast<unsigned char>(1u << k);
  return mask;
}

}  // namespace lagfsi::fluid
