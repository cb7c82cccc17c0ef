// Cell-grid neighbour search of the DEM body (src/dem/include/lagfsi/dem/dem_neighbour_grid.hpp): counting sort of
// the discs by cell, half-stencil pair search (own cell forward, E, NW, N, NE), owner CSR and incidence lists.
#include <lagfsi/dem/dem_neighbour_grid.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lagfsi::dem {

Index PairList::find(Index a, Index b) const {
  for (Index k = row[a]; k < row[a + 1]; ++k)
    if (j[k] == b) return k;
  for (Index k = row[b]; k < row[b + 1]; ++k)
    if (j[k] == a) return k;
  return -1;
}

int NeighbourGrid::cell_of(double x, double y) const {
  int cx = static_cast<int>((x - x0_) / h_), cy = static_cast<int>((y - y0_) / h_);
  cx = std::clamp(cx, 0, nx_ - 1);
  cy = std::clamp(cy, 0, ny_ - 1);
  return cy * nx_ + cx;
}

void NeighbourGrid::bin(const double* x, int stride, Index n, double cell) {
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  for (Index p = 0; p < n; ++p) {
    const double a = x[stride * p], b = x[stride * p + 1];
    if (!std::isfinite(a) || !std::isfinite(b)) throw std::runtime_error("a disc position is not finite");
    xmin = std::min(xmin, a);
    xmax = std::max(xmax, a);
    ymin = std::min(ymin, b);
    ymax = std::max(ymax, b);
  }
  if (n == 0) xmin = ymin = xmax = ymax = 0;
  h_ = cell;
  const double cap = 4.0 * n + 1024.0;
  while (((xmax - xmin) / h_ + 1) * ((ymax - ymin) / h_ + 1) > cap) h_ *= 1.5;
  x0_ = xmin;
  y0_ = ymin;
  nx_ = static_cast<int>((xmax - xmin) / h_) + 1;
  ny_ = static_cast<int>((ymax - ymin) / h_) + 1;
  const size_t nc = static_cast<size_t>(nx_) * ny_;
  cell_.resize(n);
  cell_start_.assign(nc + 1, 0);
  for (Index p = 0; p < n; ++p) {
    cell_[p] = cell_of(x[stride * p], x[stride * p + 1]);
    ++cell_start_[cell_[p] + 1];
  }
  for (size_t c = 0; c < nc; ++c) cell_start_[c + 1] += cell_start_[c];
  order_.resize(n);
  pos_.resize(n);
  std::vector<Index> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (Index p = 0; p < n; ++p) {
    const Index s = fill[cell_[p]]++;
    order_[s] = p;
    pos_[p] = s;
  }
}

void NeighbourGrid::build(const double* x, int stride, const double* r, Index n, double skin, PairList& out) const {
  if (static_cast<Index>(cell_.size()) != n) throw std::logic_error("NeighbourGrid::build before bin");
  // Visits the candidates of disc p (same cell after p in cell order, then the forward cells) and calls f(q)
  // for each listed partner.
  auto visit = [&](Index p, auto&& f) {
    const Index c = cell_[p];
    const int cx = c % nx_, cy = c / nx_;
    const double xp = x[stride * p], yp = x[stride * p + 1], rp = r[p] + skin;
    auto test = [&](Index q) {
      const double dx = x[stride * q] - xp, dy = x[stride * q + 1] - yp, s = rp + r[q];
      if (dx * dx + dy * dy < s * s) f(q);
    };
    for (Index s = pos_[p] + 1; s < cell_start_[c + 1]; ++s) test(order_[s]);
    const int dxs[4] = {1, -1, 0, 1}, dys[4] = {0, 1, 1, 1};
    for (int k = 0; k < 4; ++k) {
      const int ax = cx + dxs[k], ay = cy + dys[k];
      if (ax < 0 || ax >= nx_ || ay >= ny_) continue;
      const Index a = ay * nx_ + ax;
      for (Index s = cell_start_[a]; s < cell_start_[a + 1]; ++s) test(order_[s]);
    }
  };
  out.row.assign(n + 1, 0);
#pragma omp parallel for schedule(static) if (n >= 20000)
  for (Index p = 0; p < n; ++p) {
    Index count = 0;
    visit(p, [&](Index) { ++count; });
    out.row[p + 1] = count;
  }
  for (Index p = 0; p < n; ++p) out.row[p + 1] += out.row[p];
  const size_t np = out.row[n];
  out.i.resize(np);
  out.j.resize(np);
#pragma omp parallel for schedule(static) if (n >= 20000)
  for (Index p = 0; p < n; ++p) {
    Index k = out.row[p];
    visit(p, [&](Index q) {
      out.i[k] = p;
      out.j[k] = q;
      ++k;
    });
  }
  // Incidence, in pair order for every disc (the fixed summation order of the force sweep).
  out.inc_row.assign(n + 1, 0);
  for (size_t k = 0; k < np; ++k) {
    ++out.inc_row[out.i[k] + 1];
    ++out.inc_row[out.j[k] + 1];
  }
  for (Index p = 0; p < n; ++p) out.inc_row[p + 1] += out.inc_row[p];
  out.inc.resize(2 * np);
  std::vector<Index> fill(out.inc_row.begin(), out.inc_row.end() - 1);
  for (size_t k = 0; k < np; ++k) {
    out.inc[fill[out.i[k]]++] = static_cast<Index>(2 * k);
    out.inc[fill[out.j[k]]++] = static_cast<Index>(2 * k + 1);
  }
}

std::vector<std::pair<Index, Index>> brute_force_pairs(const double* x, int stride, const double* r, Index n,
                                                       double skin) {
  std::vector<std::pair<Index, Index>> out;
  for (Index a = 0; a < n; ++a)
    for (Index b = a + 1; b < n; ++b) {
      const double dx = x[stride * a] - x[stride * b], dy = x[stride * a + 1] - x[stride * b + 1];
      const double s = r[a] + r[b] + skin;
      if (dx * dx + dy * dy < s * s) out.emplace_back(a, b);
    }
  return out;
}

}  // namespace lagfsi::dem
