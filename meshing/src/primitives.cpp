/// @file primitives.cpp
/// Structured rectangle meshes, elevation of T3 meshes to T6 / T10 and circle arcs (no CGAL here;
/// mesh_polygon lives in polygon_mesher.cpp).
#include <lagfsi/meshing/primitives.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace lagfsi::meshing {

TriMesh mesh_rectangle_structured(double x0, double y0, double x1, double y1, int nx, int ny,
                                  const std::string& pattern) {
  const std::string where = "mesh_rectangle_structured: ";
  if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1)))
    throw std::invalid_argument(where + "non-finite corner coordinate");
  if (!(x1 > x0) || !(y1 > y0)) throw std::invalid_argument(where + "empty rectangle (need x1 > x0 and y1 > y0)");
  if (nx < 1 || ny < 1) throw std::invalid_argument(where + "nx and ny must be >= 1");
  enum class Pattern { right, left, crossed } pat;
  if (pattern == "right")
    pat = Pattern::right;
  else if (pattern == "left")
    pat = Pattern::left;
  else if (pattern == "crossed")
    pat = Pattern::crossed;
  else
    throw std::invalid_argument(where + "unknown pattern '" + pattern + "' (right, left or crossed)");
  const std::int64_t nodes = (static_cast<std::int64_t>(nx) + 1) * (static_cast<std::int64_t>(ny) + 1);
  const std::int64_t entries = 6 * static_cast<std::int64_t>(nx) * ny;
  if (nodes > std::numeric_limits<Index>::max() || entries > std::numeric_limits<Index>::max())
    throw std::invalid_argument(where + "too many cells");

  TriMesh mesh;
  mesh.order = 1;
  mesh.nodes.reserve(static_cast<std::size_t>(nodes));
  // std::lerp is exact at both ends, so the boundary nodes lie exactly on the rectangle's sides.
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.nodes.emplace_back(std::lerp(x0, x1, static_cast<double>(i) / nx),
                              std::lerp(y0, y1, static_cast<double>(j) / ny));
  mesh.conn.reserve(static_cast<std::size_t>(entries));
  auto id = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      const bool right = pat == Pattern::right || (pat == Pattern::crossed && (i + j) % 2 == 0);
      if (right)  // diagonal a-c
        mesh.conn.insert(mesh.conn.end(), {a, b, c, a, c, d});
      else  // diagonal b-d
        mesh.conn.insert(mesh.conn.end(), {a, b, d, b, c, d});
    }
  }
  return mesh;
}

TriMesh elevate(const TriMesh& linear, int order) {
  if (linear.order != 1) throw std::invalid_argument("elevate: the input mesh must be linear (order 1)");
  if (order < 1 || order > 3) throw std::invalid_argument("elevate: order must be 1, 2 or 3");
  if (linear.conn.size() % 3 != 0) throw std::invalid_argument("elevate: connectivity size is not a multiple of 3");
  const Index nv = linear.num_nodes();
  for (Index v : linear.conn)
    if (v < 0 || v >= nv) throw std::invalid_argument("elevate: node index out of range");
  if (order == 1) return linear;

  const Index ne = linear.num_elements();
  const int npe = TriMesh::nodes_per_element(order);
  TriMesh out;
  out.order = order;
  out.nodes = linear.nodes;
  out.conn.resize(static_cast<std::size_t>(ne) * npe);
  // Unique edge (min, max) -> index of its first new node. For T10 the two nodes are stored from
  // the min vertex to the max vertex (at 1/3 and 2/3 from min).
  std::unordered_map<std::uint64_t, Index> edge_nodes;
  edge_nodes.reserve(static_cast<std::size_t>(ne) * 2);
  for (Index e = 0; e < ne; ++e) {
    const Index* c = linear.element(e);
    Index* o = out.conn.data() + static_cast<std::size_t>(e) * npe;
    o[0] = c[0];
    o[1] = c[1];
    o[2] = c[2];
    for (int k = 0; k < 3; ++k) {
      const Index a = c[k], b = c[(k + 1) % 3];
      const Index lo = std::min(a, b), hi = std::max(a, b);
      const std::uint64_t key =
          (static_cast<std::uint64_t>(static_cast<std::uint32_t>(lo)) << 32) | static_cast<std::uint32_t>(hi);
      auto [it, inserted] = edge_nodes.try_emplace(key, static_cast<Index>(out.nodes.size()));
      if (inserted) {
        const Vec2& plo = linear.nodes[lo];
        const Vec2& phi = linear.nodes[hi];
        if (order == 2) {
          out.nodes.push_back(0.5 * (plo + phi));
        } else {
          out.nodes.push_back((2.0 * plo + phi) / 3.0);
          out.nodes.push_back((plo + 2.0 * phi) / 3.0);
        }
      }
      const Index first = it->second;
      if (order == 2) {
        o[3 + k] = first;
      } else {
        // Local edge k runs from a to b: its node near a comes first.
        o[3 + 2 * k] = a == lo ? first : first + 1;
        o[4 + 2 * k] = a == lo ? first + 1 : first;
      }
    }
    if (order == 3) {
      o[9] = static_cast<Index>(out.nodes.size());
      out.nodes.push_back((linear.nodes[c[0]] + linear.nodes[c[1]] + linear.nodes[c[2]]) / 3.0);
    }
    if (out.nodes.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
      throw std::invalid_argument("elevate: too many nodes");
  }
  return out;
}

std::vector<Vec2> arc_points(const Vec2& centre, double radius, double a0, double a1, double h) {
  if (!(std::isfinite(centre.x()) && std::isfinite(centre.y()) && std::isfinite(a0) && std::isfinite(a1)))
    throw std::invalid_argument("arc_points: non-finite centre or angle");
  if (!std::isfinite(radius) || !(radius > 0.0))
    throw std::invalid_argument("arc_points: radius must be finite and > 0");
  if (!std::isfinite(h) || !(h > 0.0)) throw std::invalid_argument("arc_points: h must be finite and > 0");
  // A chord is shorter than its arc: arc pieces of length <= h give segments <= h.
  const double pieces = std::ceil(std::abs(a1 - a0) * radius / h * (1.0 - 1e-12));
  if (!(pieces <= 1e7)) throw std::invalid_argument("arc_points: too many points (h too small for the arc)");
  const int n = std::max(1, static_cast<int>(pieces));
  std::vector<Vec2> pts;
  pts.reserve(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double a = std::lerp(a0, a1, static_cast<double>(k) / n);
    pts.emplace_back(centre.x() + radius * std::cos(a), centre.y() + radius * std::sin(a));
  }
  return pts;
}

}  // namespace lagfsi::meshing
