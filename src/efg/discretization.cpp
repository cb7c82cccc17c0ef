// Background quadrilateral meshes, Gauss rules, Q4 functions, visibility and node search for the EFG module
// (thesis §2.6-2.7, §4.4). See src/efg/include/lagfsi/efg/discretization.hpp.
#include <lagfsi/efg/discretization.hpp>

#include <lagfsi/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace lagfsi::efg {

namespace {
/// Drops nodes used by no cell and renumbers (q9: the cells' nine nodes, else their corners).
QuadMesh compact(const std::vector<Vec2>& nodes, const std::vector<std::array<Index, 4>>& cells,
                 const std::vector<std::array<Index, 9>>& q9 = {}) {
  std::vector<Index> map(nodes.size(), -1);
  QuadMesh m;
  for (const auto& c : cells)
    for (Index n : c) map[n] = 0;
  for (const auto& c : q9)
    for (Index n : c) map[n] = 0;
  // Keep the original node order (sorted by old index) for readable numbering.
  std::vector<Index> order;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (map[i] >= 0) order.push_back(static_cast<Index>(i));
  m.nodes.clear();
  for (size_t k = 0; k < order.size(); ++k) {
    map[order[k]] = static_cast<Index>(k);
    m.nodes.push_back(nodes[order[k]]);
  }
  for (const auto& c : cells) m.cells.push_back({map[c[0]], map[c[1]], map[c[2]], map[c[3]]});
  for (const auto& c : q9) {
    std::array<Index, 9> r;
    for (int a = 0; a < 9; ++a) r[a] = map[c[a]];
    m.q9.push_back(r);
  }
  return m;
}
}  // namespace

QuadMesh rectangle_grid(Vec2 origin, Vec2 size, int nx, int ny, const std::vector<std::array<Vec2, 2>>& holes,
                        int order) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("divisions must be at least 1");
  if (order != 1 && order != 2) throw std::invalid_argument("cell order must be 1 (Q4) or 2 (Q9)");
  const int mx = order * nx, my = order * ny;  // node intervals
  std::vector<Vec2> nodes;
  for (int j = 0; j <= my; ++j)
    for (int i = 0; i <= mx; ++i) nodes.emplace_back(origin.x() + size.x() * i / mx, origin.y() + size.y() * j / my);
  auto id = [&](int i, int j) { return static_cast<Index>(j * (mx + 1) + i); };
  std::vector<std::array<Index, 4>> cells;
  std::vector<std::array<Index, 9>> q9;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int I = order * i, J = order * j, o = order;
      const std::array<Index, 4> c = {id(I, J), id(I + o, J), id(I + o, J + o), id(I, J + o)};
      const Vec2 ctr = 0.25 * (nodes[c[0]] + nodes[c[1]] + nodes[c[2]] + nodes[c[3]]);
      bool removed = false;
      for (const auto& h : holes)
        if (ctr.x() > h[0].x() && ctr.x() < h[1].x() && ctr.y() > h[0].y() && ctr.y() < h[1].y()) removed = true;
      if (removed) continue;
      cells.push_back(c);
      if (order == 2)
        q9.push_back(
            {c[0], c[1], c[2], c[3], id(I + 1, J), id(I + 2, J + 1), id(I + 1, J + 2), id(I, J + 1), id(I + 1, J + 1)});
    }
  if (cells.empty()) throw std::invalid_argument("the holes remove every cell");
  return compact(nodes, cells, q9);
}

QuadMesh plate_with_hole(double a, double b, int n_arc, int n_rad, double grading) {
  if (!(a > 0 && b > a) || n_arc < 1 || n_rad < 1 || !(grading > 0))
    throw std::invalid_argument("plate_with_hole needs 0 < radius < size, divisions >= 1, grading > 0");
  // Radial parameter s_k in [0, 1], geometric sizes with last/first = grading.
  std::vector<double> s(n_rad + 1, 0.0);
  const double q = n_rad > 1 ? std::pow(grading, 1.0 / (n_rad - 1)) : 1.0;
  double tot = 0, d = 1;
  for (int k = 0; k < n_rad; ++k, d *= q) tot += d;
  d = 1;
  for (int k = 1; k <= n_rad; ++k, d *= q) s[k] = s[k - 1] + d / tot;
  // Angles 0..pi/2 in 2 n_arc cells; outer point on the square boundary along the same parameter.
  const int na = 2 * n_arc;
  std::vector<Vec2> nodes;
  for (int k = 0; k <= n_rad; ++k)
    for (int i = 0; i <= na; ++i) {
      const double th = 0.5 * M_PI * i / na;
      const Vec2 inner(a * std::cos(th), a * std::sin(th));
      // Outer boundary: x = b for th <= 45 deg (y linear), y = b above (x linear): straight edges evenly divided.
      Vec2 outer;
      if (i <= n_arc)
        outer = Vec2(b, b * static_cast<double>(i) / n_arc);
      else
        outer = Vec2(b * static_cast<double>(na - i) / n_arc, b);
      nodes.push_back(inner + s[k] * (outer - inner));
    }
  std::vector<std::array<Index, 4>> cells;
  for (int k = 0; k < n_rad; ++k)
    for (int i = 0; i < na; ++i) {
      const Index p = k * (na + 1) + i;
      cells.push_back({p, p + na + 1, p + na + 2, p + 1});  // counter-clockwise (radial out, then angle)
    }
  return compact(nodes, cells);
}

std::vector<std::array<Index, 2>> boundary_cell_edges(const QuadMesh& m) {
  std::map<std::pair<Index, Index>, std::pair<Index, int>> count;
  std::map<std::pair<Index, Index>, int> uses;
  for (Index c = 0; c < m.num_cells(); ++c)
    for (int k = 0; k < 4; ++k) {
      Index a = m.cells[c][k], b = m.cells[c][(k + 1) % 4];
      auto key = std::minmax(a, b);
      ++uses[key];
      count[key] = {c, k};
    }
  std::vector<std::array<Index, 2>> out;
  for (const auto& [key, u] : uses)
    if (u == 1) out.push_back({count[key].first, count[key].second});
  std::sort(out.begin(), out.end());
  return out;
}

void q4_shape(double xi, double eta, double N[4], double dxi[4], double deta[4]) {
  static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  for (int a = 0; a < 4; ++a) {
    N[a] = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
    dxi[a] = 0.25 * sx[a] * (1 + sy[a] * eta);
    deta[a] = 0.25 * sy[a] * (1 + sx[a] * xi);
  }
}

void q9_shape(double xi, double eta, double N[9], double dxi[9], double deta[9]) {
  // 1-D quadratic Lagrange functions at -1, 0, 1 and their derivatives.
  auto l = [](double s, double v[3], double d[3]) {
    v[0] = 0.5 * s * (s - 1);
    v[1] = 1 - s * s;
    v[2] = 0.5 * s * (s + 1);
    d[0] = s - 0.5;
    d[1] = -2 * s;
    d[2] = s + 0.5;
  };
  double lx[3], dx[3], ly[3], dy[3];
  l(xi, lx, dx);
  l(eta, ly, dy);
  // Local node -> (index in x, index in y) of the 3 x 3 tensor grid.
  static const int ix[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, iy[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
  for (int a = 0; a < 9; ++a) {
    N[a] = lx[ix[a]] * ly[iy[a]];
    dxi[a] = dx[ix[a]] * ly[iy[a]];
    deta[a] = lx[ix[a]] * dy[iy[a]];
  }
}

void cell_node_natural(int a, double& xi, double& eta) {
  static const double cx[9] = {-1, 1, 1, -1, 0, 1, 0, -1, 0}, cy[9] = {-1, -1, 1, 1, -1, 0, 1, 0, 0};
  xi = cx[a];
  eta = cy[a];
}

void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  if (n < 1 || n > 12) throw std::invalid_argument("Gauss order must be 1..12");
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  // Newton on the Legendre polynomial (Numerical Recipes gauleg).
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), pp = 0;
    for (int it = 0; it < 100; ++it) {
      double p1 = 1, p2 = 0;
      for (int j = 1; j <= n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j - 1) * z * p2 - (j - 1.0) * p3) / j;
      }
      pp = n * (z * p1 - p2) / (z * z - 1);
      const double z1 = z;
      z = z1 - p1 / pp;
      if (std::abs(z - z1) < 1e-15) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    w[i] = w[n - 1 - i] = 2.0 / ((1 - z * z) * pp * pp);
  }
  if (n % 2 == 1) x[n / 2] = 0.0;
}

bool Visibility::visible(const Vec2& a, const Vec2& b) const {
  for (const auto& s : segments) {
    const Vec2 r = b - a, q = s[1] - s[0];
    const double den = cross(r, q);
    if (std::abs(den) < 1e-300) continue;  // parallel: no proper crossing
    const double t = cross(s[0] - a, q) / den, u = cross(s[0] - a, r) / den;
    const double e = 1e-12;
    if (t > e && t < 1 - e && u > -e && u < 1 + e) return false;
  }
  return true;
}

NodeSearch::NodeSearch(const std::vector<Vec2>& nodes, double cell_size) : nodes_(&nodes), h_(cell_size) {
  Vec2 lo = nodes.front(), hi = nodes.front();
  for (const auto& p : nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo_ = lo;
  // Buckets no smaller than the search radius, and no more than about 4 per node: a radius far below the node
  // spacing (a tiny alpha) would otherwise ask for billions of empty buckets.
  const double extent = (hi - lo).maxCoeff();
  h_ = std::max(h_, extent / (2.0 * std::sqrt(static_cast<double>(nodes.size())) + 1.0));
  if (!(h_ > 0)) h_ = 1.0;  // a single node
  nx_ = std::max(1, static_cast<int>((hi.x() - lo.x()) / h_) + 1);
  ny_ = std::max(1, static_cast<int>((hi.y() - lo.y()) / h_) + 1);
  bucket_.assign(static_cast<size_t>(nx_) * ny_, {});
  for (size_t i = 0; i < nodes.size(); ++i) {
    const int bx = std::min(nx_ - 1, static_cast<int>((nodes[i].x() - lo_.x()) / h_));
    const int by = std::min(ny_ - 1, static_cast<int>((nodes[i].y() - lo_.y()) / h_));
    bucket_[static_cast<size_t>(by) * nx_ + bx].push_back(static_cast<Index>(i));
  }
}

void NodeSearch::within(const Vec2& x, double r, std::vector<Index>& out) const {
  out.clear();
  // Bucket indices clamped in floating point first (a radius far beyond the body would overflow an int).
  auto bucket = [this](double v, int n) { return static_cast<int>(std::clamp(std::floor(v / h_), 0.0, n - 1.0)); };
  const int x0 = bucket(x.x() - r - lo_.x(), nx_), x1 = bucket(x.x() + r - lo_.x(), nx_);
  const int y0 = bucket(x.y() - r - lo_.y(), ny_), y1 = bucket(x.y() + r - lo_.y(), ny_);
  for (int by = y0; by <= y1; ++by)
    for (int bx = x0; bx <= x1; ++bx)
      for (Index j : bucket_[static_cast<size_t>(by) * nx_ + bx]) {
        const Vec2 d = (*nodes_)[j] - x;
        if (std::abs(d.x()) <= r && std::abs(d.y()) <= r) out.push_back(j);
      }
  std::sort(out.begin(), out.end());
}

}  // namespace lagfsi::efg
