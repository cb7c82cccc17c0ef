// The pressure level of water that no boundary sets (pressure_level.hpp): the connected parts of the mesh by a
// union-find over its elements, each part's anchors, and a pinned pressure where a part has none.
#include "pressure_level.hpp"

#include <numeric>

namespace lagfsi::fluid {

namespace {

/// The root of i's set, halving the path on the way.
Index root(std::vector<Index>& parent, Index i) {
  while (parent[static_cast<size_t>(i)] != i) {
    parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    i = parent[static_cast<size_t>(i)];
  }
  return i;
}

}  // namespace

PressureLevelParts anchor_pressure_level(const FluidMesh& mesh, const ParticleCloud& cloud,
                                         const std::vector<std::uint8_t>& free, const std::vector<int>& inflow,
                                         const Vec2& gravity, double bulk, std::vector<char>& fixed) {
  PressureLevelParts out;
  if (bulk > 0 || mesh.tri.empty()) return out;
  const Index np = cloud.n();
  std::vector<Index> parent(static_cast<size_t>(np));
  std::iota(parent.begin(), parent.end(), Index{0});
  std::vector<char> meshed(static_cast<size_t>(np), 0);
  for (const auto& t : mesh.tri)
    for (int k = 0; k < 3; ++k) {
      meshed[static_cast<size_t>(t[k])] = 1;
      const Index a = root(parent, t[k]), b = root(parent, t[(k + 1) % 3]);
      if (a != b) parent[static_cast<size_t>(a)] = b;
    }
  // Per part (by its root): whether something sets its level, the inflow that feeds it and its highest particle.
  const Vec2 up = gravity.norm() > 0 ? Vec2(-gravity.normalized()) : Vec2(0.0, 1.0);
  std::vector<char> anchored(static_cast<size_t>(np), 0);
  std::vector<int> fed(static_cast<size_t>(np), -1);
  std::vector<Index> top(static_cast<size_t>(np), -1);
  for (Index i = 0; i < np; ++i) {
    const auto k = static_cast<size_t>(i);
    if (!meshed[k]) continue;
    const auto r = static_cast<size_t>(root(parent, i));
    // An inlet's particles set no level (pressure_level.hpp).
    const bool inlet = k < inflow.size() && inflow[k] >= 0;
    if (inlet && fed[r] < 0) fed[r] = inflow[k];
    if (!inlet && (fixed[3 * k + 2] || (k < free.size() && free[k]))) anchored[r] = 1;
    if (!cloud.is_fluid(i)) continue;
    const Index best = top[r];
    // The highest; between equals (a flat top) the first, so that the choice does not depend on round-off.
    if (best < 0 || cloud.pos(i).dot(up) > cloud.pos(best).dot(up) + 1e-9 * cloud.h(i)) top[r] = i;
  }
  for (Index i = 0; i < np; ++i) {
    const auto r = static_cast<size_t>(i);
    if (!meshed[r] || parent[r] != i || anchored[r] || top[r] < 0) continue;  // roots of unanchored parts only
    if (fed[r] >= 0) {
      if (out.inflow < 0) out.inflow = fed[r];
      continue;
    }
    fixed[3 * static_cast<size_t>(top[r]) + 2] = 1;
    ++out.pinned;
  }
  return out;
}

}  // namespace lagfsi::fluid
