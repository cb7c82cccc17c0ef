/// @file previous_domain.cpp
/// Point location in the advected previous domain and distance to its boundary (previous_domain.hpp).
#include <lagfsi/meshing/previous_domain.hpp>

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lagfsi::meshing {

int PreviousDomain::Grid::cx(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - lo.x()) / cell)), 0, nx - 1);
}
int PreviousDomain::Grid::cy(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - lo.y()) / cell)), 0, ny - 1);
}

PreviousDomain::Grid PreviousDomain::bucket(const std::vector<std::array<Vec2, 2>>& boxes, const Vec2& lo,
                                            const Vec2& hi, double cell) {
  Grid g;
  g.lo = lo;
  g.cell = cell;
  g.nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)));
  g.ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)));
  const std::size_t cells = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::vector<int> count(cells + 1, 0);
  auto each = [&](const std::array<Vec2, 2>& b, auto&& f) {
    const int x0 = g.cx(b[0].x()), x1 = g.cx(b[1].x()), y0 = g.cy(b[0].y()), y1 = g.cy(b[1].y());
    for (int j = y0; j <= y1; ++j)
      for (int i = x0; i <= x1; ++i) f(static_cast<std::size_t>(j) * g.nx + i);
  };
  for (const auto& b : boxes) each(b, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  g.start = count;
  g.items.resize(static_cast<std::size_t>(count[cells]));
  for (std::size_t k = 0; k < boxes.size(); ++k)
    each(boxes[k], [&](std::size_t c) { g.items[static_cast<std::size_t>(count[c]++)] = static_cast<int>(k); });
  return g;
}

PreviousDomain::PreviousDomain(std::vector<std::array<Vec2, 3>> triangles, std::vector<std::array<Vec2, 2>> boundary)
    : triangles_(std::move(triangles)), boundary_(std::move(boundary)) {
  if (triangles_.empty()) return;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<std::array<Vec2, 2>> boxes(triangles_.size());
  double size = 0;
  // Each element's orientation (0: flat) and the tolerance of contains()' edge tests, -1e-12 |2 A|.
  sign_.resize(triangles_.size());
  tolerance_.resize(triangles_.size());
  for (std::size_t e = 0; e < triangles_.size(); ++e) {
    const auto& t = triangles_[e];
    const double a2 = cross(t[1] - t[0], t[2] - t[0]);
    sign_[e] = a2 > 0 ? 1.0 : a2 < 0 ? -1.0 : 0.0;
    tolerance_[e] = -1e-12 * std::abs(a2);
    boxes[e] = {t[0].cwiseMin(t[1]).cwiseMin(t[2]), t[0].cwiseMax(t[1]).cwiseMax(t[2])};
    lo = lo.cwiseMin(boxes[e][0]);
    hi = hi.cwiseMax(boxes[e][1]);
    size += (boxes[e][1] - boxes[e][0]).maxCoeff();
  }
  // About one element per cell, but never more cells than 4 per element (drops far apart).
  const Vec2 ext = (hi - lo).cwiseMax(Vec2::Constant(1e-300));
  double cell = std::max(size / static_cast<double>(triangles_.size()), 1e-300);
  cell = std::max(cell, std::sqrt(ext.x() * ext.y() / (4.0 * static_cast<double>(triangles_.size()))));
  tri_grid_ = bucket(boxes, lo, hi, cell);
  std::vector<std::array<Vec2, 2>> eboxes(boundary_.size());
  for (std::size_t k = 0; k < boundary_.size(); ++k)
    eboxes[k] = {boundary_[k][0].cwiseMin(boundary_[k][1]), boundary_[k][0].cwiseMax(boundary_[k][1])};
  edge_grid_ = bucket(eboxes, lo, hi, cell);
}

bool PreviousDomain::contains(const Vec2& p) const {
  if (triangles_.empty()) return false;
  const Grid& g = tri_grid_;
  if (p.x() < g.lo.x() || p.y() < g.lo.y() || p.x() > g.lo.x() + g.nx * g.cell || p.y() > g.lo.y() + g.ny * g.cell)
    return false;
  const std::size_t c = static_cast<std::size_t>(g.cy(p.y())) * g.nx + g.cx(p.x());
  for (int k = g.start[c]; k < g.start[c + 1]; ++k) {
    const auto e = static_cast<std::size_t>(g.items[static_cast<std::size_t>(k)]);
    const auto& t = triangles_[e];
    const double s = sign_[e], tol = tolerance_[e];
    if (s == 0) continue;
    if (s * cross(t[1] - t[0], p - t[0]) >= tol && s * cross(t[2] - t[1], p - t[1]) >= tol &&
        s * cross(t[0] - t[2], p - t[2]) >= tol)
      return true;
  }
  return false;
}

double PreviousDomain::boundary_distance(const Vec2& p, double limit) const {
  if (boundary_.empty()) return limit;
  const Grid& g = edge_grid_;
  double best = limit;
  const int x0 = g.cx(p.x() - limit), x1 = g.cx(p.x() + limit), y0 = g.cy(p.y() - limit), y1 = g.cy(p.y() + limit);
  for (int j = y0; j <= y1; ++j)
    for (int i = x0; i <= x1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * g.nx + i;
      for (int k = g.start[c]; k < g.start[c + 1]; ++k) {
        const auto& e = boundary_[static_cast<std::size_t>(g.items[static_cast<std::size_t>(k)])];
        best = std::min(best, segment_distance(p, e[0], e[1]));
      }
    }
  return best;
}

void PreviousDomain::set_topology(std::vector<std::uint8_t> meshed, std::vector<std::pair<Index, Index>> edges) {
  meshed_ = std::move(meshed);
  for (auto& e : edges)
    if (e.first > e.second) std::swap(e.first, e.second);
  std::sort(edges.begin(), edges.end());
  boundary_edges_ = std::move(edges);
}

void PreviousDomain::set_edges(std::vector<std::pair<Index, Index>> edges) {
  for (auto& e : edges)
    if (e.first > e.second) std::swap(e.first, e.second);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  edges_ = std::move(edges);
}

bool PreviousDomain::is_edge(Index a, Index b) const {
  const std::pair<Index, Index> e = std::minmax(a, b);
  return std::binary_search(edges_.begin(), edges_.end(), e);
}

bool PreviousDomain::meshed(Index i) const {
  return meshed_.empty() ||
         (i >= 0 && static_cast<std::size_t>(i) < meshed_.size() && meshed_[static_cast<std::size_t>(i)]);
}

bool PreviousDomain::is_boundary_edge(Index a, Index b) const {
  const std::pair<Index, Index> e = std::minmax(a, b);
  return std::binary_search(boundary_edges_.begin(), boundary_edges_.end(), e);
}

double PreviousDomain::area() const {
  double a = 0;
  for (const auto& t : triangles_) a += 0.5 * std::abs(cross(t[1] - t[0], t[2] - t[0]));
  return a;
}

}  // namespace lagfsi::meshing
