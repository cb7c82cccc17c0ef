// The particles divided among processes by space, and each part's share of the Delaunay triangulation
// (partition.hpp).
#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace lagfsi::meshing {

SpacePartition::SpacePartition(const std::vector<Vec2>& points, int parts) {
  if (parts < 1) throw std::invalid_argument("SpacePartition: at least one part (got " + std::to_string(parts) + ")");
  owner_.assign(points.size(), 0);
  std::vector<Index> ids(points.size());
  std::iota(ids.begin(), ids.end(), Index{0});
  const double inf = std::numeric_limits<double>::infinity();
  root_ = divide(ids, 0, ids.size(), parts, points, {Vec2(-inf, -inf), Vec2(inf, inf)});
}

int SpacePartition::divide(std::vector<Index>& ids, size_t from, size_t to, int parts, const std::vector<Vec2>& points,
                           std::pair<Vec2, Vec2> box) {
  if (parts == 1) {
    const int part = static_cast<int>(boxes_.size());
    boxes_.push_back(box);
    for (size_t k = from; k < to; ++k) owner_[static_cast<size_t>(ids[k])] = part;
    return -1 - part;
  }
  // Across the longer side of the points' bounding box (of the box itself when it holds no point).
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (size_t k = from; k < to; ++k) {
    lo = lo.cwiseMin(points[static_cast<size_t>(ids[k])]);
    hi = hi.cwiseMax(points[static_cast<size_t>(ids[k])]);
  }
  Cut cut;
  cut.axis = to > from && hi.y() - lo.y() > hi.x() - lo.x() ? 1 : 0;
  const int low_parts = parts / 2;
  const size_t n_low = from + (to - from) * static_cast<size_t>(low_parts) / static_cast<size_t>(parts);
  const int axis = cut.axis;
  // Points ordered by the coordinate, ties by index: the same cut whatever order the points came in.
  const auto before = [&](Index a, Index b) {
    const double xa = points[static_cast<size_t>(a)][axis], xb = points[static_cast<size_t>(b)][axis];
    return xa < xb || (xa == xb && a < b);
  };
  if (n_low > from && n_low < to) {
    // Between the n_low-th point and the next.
    std::nth_element(ids.begin() + static_cast<long>(from), ids.begin() + static_cast<long>(n_low),
                     ids.begin() + static_cast<long>(to), before);
    double low_max = -std::numeric_limits<double>::infinity();
    for (size_t k = from; k < n_low; ++k) low_max = std::max(low_max, points[static_cast<size_t>(ids[k])][axis]);
    cut.at = 0.5 * (low_max + points[static_cast<size_t>(ids[n_low])][axis]);
  } else if (to > from) {  // too few points to divide in proportion: their middle
    cut.at = 0.5 * (lo[axis] + hi[axis]);
  } else {  // no point: anywhere inside the box
    const double a = box.first[axis], b = box.second[axis];
    cut.at = std::isfinite(a) && std::isfinite(b) ? 0.5 * (a + b)
             : std::isfinite(a)                   ? a + 1.0
             : std::isfinite(b)                   ? b - 1.0
                                                  : 0.0;
  }
  // Points exactly on the cut belong to the high side ([lo, hi) boxes).
  size_t split = from;
  for (size_t k = from; k < to; ++k)
    if (points[static_cast<size_t>(ids[k])][axis] < cut.at) std::swap(ids[k], ids[split++]);
  std::pair<Vec2, Vec2> low_box = box, high_box = box;
  low_box.second[axis] = cut.at;
  high_box.first[axis] = cut.at;
  const int k = static_cast<int>(cuts_.size());
  cuts_.push_back(cut);
  const int low = divide(ids, from, split, low_parts, points, low_box);
  const int high = divide(ids, split, to, parts - low_parts, points, high_box);
  cuts_[static_cast<size_t>(k)].low = low;
  cuts_[static_cast<size_t>(k)].high = high;
  return k;
}

int SpacePartition::part_of(const Vec2& x) const {
  int node = root_;
  while (node >= 0) {
    const Cut& c = cuts_[static_cast<size_t>(node)];
    node = x[c.axis] < c.at ? c.low : c.high;
  }
  return -1 - node;
}

std::vector<Index> SpacePartition::ghosts(const std::vector<Vec2>& points, int part, double halo) const {
  const auto& [lo, hi] = box(part);
  std::vector<Index> g;
  for (size_t i = 0; i < points.size(); ++i) {
    if (owner_[i] == part) continue;
    const Vec2 out = (lo - points[i]).cwiseMax(points[i] - hi).cwiseMax(Vec2::Zero());
    // A hair wider than the halo: a kept triangle's circumcentre is computed, not exact.
    if (out.norm() <= halo * (1 + 1e-9)) g.push_back(static_cast<Index>(i));
  }
  return g;
}

std::vector<Index> SpacePartition::local(const std::vector<Vec2>& points, int part, double halo,
                                         Index* ghost_count) const {
  std::vector<Index> ids;
  for (size_t i = 0; i < points.size(); ++i)
    if (owner_[i] == part) ids.push_back(static_cast<Index>(i));
  const std::vector<Index> g = ghosts(points, part, halo);
  if (ghost_count != nullptr) *ghost_count = static_cast<Index>(g.size());
  ids.insert(ids.end(), g.begin(), g.end());
  return ids;
}

std::pair<Vec2, double> circumcircle(const std::vector<Vec2>& points, std::array<Index, 3> t) {
  std::sort(t.begin(), t.end());
  const Vec2 a = points[static_cast<size_t>(t[0])];
  const Vec2 b = points[static_cast<size_t>(t[1])] - a, c = points[static_cast<size_t>(t[2])] - a;
  const double d = 2.0 * (b.x() * c.y() - b.y() * c.x());
  if (d == 0.0) return {a, std::numeric_limits<double>::infinity()};
  const Vec2 u((c.y() * b.squaredNorm() - b.y() * c.squaredNorm()) / d,
               (b.x() * c.squaredNorm() - c.x() * b.squaredNorm()) / d);
  return {a + u, u.norm()};
}

std::vector<std::array<Index, 3>> part_delaunay(const std::vector<Vec2>& points, const SpacePartition& partition,
                                                int part, double halo, Index* ghost_count) {
  // The part's points, then its ghosts; the local triangulation in global indices.
  const std::vector<Index> local = partition.local(points, part, halo, ghost_count);
  std::vector<Vec2> pts;
  pts.reserve(local.size());
  for (Index i : local) pts.push_back(points[static_cast<size_t>(i)]);
  std::vector<std::array<Index, 3>> kept;
  for (auto t : delaunay_triangles(pts)) {
    for (Index& v : t) v = local[static_cast<size_t>(v)];
    const auto [centre, radius] = circumcircle(points, t);
    if (radius <= halo && partition.part_of(centre) == part) kept.push_back(t);
  }
  return kept;
}

}  // namespace lagfsi::meshing
