// The step's mesh of the fluid particles (fluid_mesh.hpp): connectivity, area and neighbourhood queries.
#include "fluid_mesh.hpp"

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

}  // namespace lagfsi::fluid
