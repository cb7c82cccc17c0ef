/// @file particle_quality.cpp
/// The geometric part of the PFEM's particle-quality control on a mesh (remesh.hpp): fluid particles closer than a
/// fraction of their size, and elements too large for their particles.
#include <lagfsi/meshing/remesh.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace lagfsi::meshing {

namespace {

[[noreturn]] void fail(const char* where, const std::string& what) {
  throw std::invalid_argument(std::string(where) + ": " + what);
}

void check_triangles(const std::vector<std::array<Index, 3>>& triangles, std::size_t n, const char* where) {
  for (std::size_t e = 0; e < triangles.size(); ++e)
    for (Index v : triangles[e])
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        fail(where, "triangle " + std::to_string(e) + " has particle index " + std::to_string(v) +
                        " out of range [0, " + std::to_string(n) + ")");
}

}  // namespace

std::vector<Index> close_fluid_particles(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                                         const std::vector<double>& h,
                                         const std::vector<std::array<Index, 3>>& triangles, double fraction) {
  std::vector<Index> remove;
  for (const auto& pr : close_fluid_pairs(points, kind, h, triangles, fraction)) remove.push_back(pr.second);
  std::sort(remove.begin(), remove.end());
  return remove;
}

std::vector<std::pair<Index, Index>> close_fluid_pairs(const std::vector<Vec2>& points,
                                                       const std::vector<ParticleKind>& kind,
                                                       const std::vector<double>& h,
                                                       const std::vector<std::array<Index, 3>>& triangles,
                                                       double fraction) {
  const char* where = "close_fluid_particles";
  const std::size_t n = points.size();
  if (kind.size() != n || h.size() != n) fail(where, "sizes of points, kind and h do not match");
  if (!(std::isfinite(fraction) && fraction >= 0)) fail(where, "fraction must be finite and >= 0");
  check_triangles(triangles, n, where);

  // Candidates (relative distance squared, smaller index, larger index); each interior edge appears
  // twice, the second copy is skipped below because one of its particles is already removed.
  std::vector<std::tuple<double, Index, Index>> close;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      Index i = t[static_cast<std::size_t>(k)], j = t[static_cast<std::size_t>((k + 1) % 3)];
      const auto si = static_cast<std::size_t>(i), sj = static_cast<std::size_t>(j);
      if (kind[si] != ParticleKind::Fluid || kind[sj] != ParticleKind::Fluid) continue;
      const double hij = 0.5 * (h[si] + h[sj]);
      const double d2 = (points[si] - points[sj]).squaredNorm();
      const double lim = fraction * hij;
      if (d2 < lim * lim) {
        if (i > j) std::swap(i, j);
        close.emplace_back(d2 / (hij * hij), i, j);
      }
    }
  }
  std::vector<std::pair<Index, Index>> pairs;
  if (close.empty()) return pairs;
  std::sort(close.begin(), close.end());
  std::vector<std::uint8_t> removed(n, 0);
  for (const auto& [r2, i, j] : close) {
    (void)r2;
    if (removed[static_cast<std::size_t>(i)] || removed[static_cast<std::size_t>(j)]) continue;
    removed[static_cast<std::size_t>(j)] = 1;
    pairs.emplace_back(i, j);
  }
  return pairs;
}

std::vector<Index> oversized_elements(const std::vector<Vec2>& points, const std::vector<double>& h,
                                      const std::vector<std::array<Index, 3>>& triangles, double factor) {
  const char* where = "oversized_elements";
  if (h.size() != points.size()) fail(where, "sizes of points and h do not match");
  if (!(std::isfinite(factor) && factor >= 0)) fail(where, "factor must be finite and >= 0");
  check_triangles(triangles, points.size(), where);
  std::vector<Index> out;
  for (std::size_t e = 0; e < triangles.size(); ++e) {
    const auto a = static_cast<std::size_t>(triangles[e][0]), b = static_cast<std::size_t>(triangles[e][1]),
               c = static_cast<std::size_t>(triangles[e][2]);
    const Vec2 u = points[b] - points[a], v = points[c] - points[a];
    const double area = 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
    const double he = (h[a] + h[b] + h[c]) / 3.0;
    if (area > factor * he * he) out.push_back(static_cast<Index>(e));
  }
  return out;
}

}  // namespace lagfsi::meshing
