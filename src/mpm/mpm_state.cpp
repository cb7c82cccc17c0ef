// State of an MPM body (src/mpm/include/lagfsi/mpm/mpm_state.hpp): particles, the background grid and the shape
// functions, linear (tent functions of the cells) or uGIMP (Bardenhagen & Kober 2004): the particle's
// characteristic function of half-width lp (in cells) convolved with the tent function,
//   S(r) = 1 - (r^2 + lp^2) / (2 lp)          |r| < lp
//          1 - |r|                            lp <= |r| < 1 - lp
//          (1 + lp - |r|)^2 / (4 lp)          1 - lp <= |r| < 1 + lp
// per direction, the 2D function the product of the two.
#include <lagfsi/mpm/mpm_state.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::mpm {

void Particles::add(const Vec2& position, double particle_mass, double particle_volume) {
  x.push_back(position);
  X.push_back(position);
  v.push_back(Vec2::Zero());
  mass.push_back(particle_mass);
  volume0.push_back(particle_volume);
  volume.push_back(particle_volume);
  F.push_back(Mat2::Identity());
  stress.push_back({0, 0, 0, 0});
  strain.push_back({0, 0, 0});
  plastic_multiplier.push_back(0.0);
  strain_rate.push_back({0, 0, 0});
  porosity.push_back(0.0);
  pore_pressure.push_back(0.0);
  water_velocity.push_back(Vec2::Zero());
  acceleration.push_back(Vec2::Zero());
}

std::vector<Vec2> Grid::node_positions() const {
  std::vector<Vec2> nodes;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) nodes.push_back(node_position(i, j));
  return nodes;
}

void Grid::allocate() {
  const size_t nn = num_nodes();
  mass.assign(nn, 0.0);
  momentum.assign(nn, Vec2::Zero());
  force.assign(nn, Vec2::Zero());
  velocity.assign(nn, Vec2::Zero());
}

namespace {

/// ShapeFunctions::evaluate, inlined into the particle loop of locate_particles (one call per particle and
/// sub-step otherwise).
[[gnu::always_inline]] inline void evaluate_support(const Grid& grid, bool gimp, int particles_per_cell, const Vec2& x,
                                                    Support& s) {
  // Per direction: the nodes within reach and the 1D function and its derivative.
  const double h = grid.h;
  std::array<std::array<double, 3>, 2> w{}, dw{};
  std::array<int, 2> first{}, count{};
  for (int c = 0; c < 2; ++c) {
    const double xi = (x[c] - grid.origin[c]) / h;  // in cells
    const int n_cells = c == 0 ? grid.nx : grid.ny;
    if (!gimp) {
      int i = static_cast<int>(std::floor(xi));
      i = std::clamp(i, 0, n_cells - 1);
      const double r = xi - i;
      first[c] = i;
      count[c] = 2;
      w[c] = {1.0 - r, r, 0.0};
      dw[c] = {-1.0 / h, 1.0 / h, 0.0};
    } else {
      const double lp = 0.5 / particles_per_cell;  // particle half-width in cells
      const int i0 = std::max(0, static_cast<int>(std::floor(xi - lp)));
      const int i1 = std::min(n_cells, static_cast<int>(std::floor(xi + lp)) + 1);
      first[c] = i0;
      count[c] = std::min(3, i1 - i0 + 1);
      for (int k = 0; k < count[c]; ++k) {
        const double r = xi - (i0 + k), a = std::abs(r), sg = r < 0 ? -1.0 : 1.0;
        double f = 0, df = 0;
        if (a < lp) {
          f = 1.0 - (r * r + lp * lp) / (2.0 * lp);
          df = -r / lp;
        } else if (a < 1.0 - lp) {
          f = 1.0 - a;
          df = -sg;
        } else if (a < 1.0 + lp) {
          f = (1.0 + lp - a) * (1.0 + lp - a) / (4.0 * lp);
          df = -sg * (1.0 + lp - a) / (2.0 * lp);
        }
        w[c][k] = f;
        dw[c][k] = df / h;
      }
    }
  }
  s.n = 0;
  for (int b = 0; b < count[1]; ++b)
    for (int a = 0; a < count[0]; ++a) {
      const double N = w[0][a] * w[1][b];
      const Vec2 dN(dw[0][a] * w[1][b], w[0][a] * dw[1][b]);
      if (N == 0.0 && dN.squaredNorm() == 0.0) continue;
      s.node[s.n] = (first[1] + b) * (grid.nx + 1) + first[0] + a;
      s.N[s.n] = N;
      s.dN[s.n] = dN;
      ++s.n;
    }
}

}  // namespace

void ShapeFunctions::evaluate(const Grid& grid, const Vec2& x, Support& s) const {
  evaluate_support(grid, gimp, particles_per_cell, x, s);
}

Index locate_particles(const Grid& grid, const ShapeFunctions& shape, const Particles& particles,
                       std::vector<Support>& support) {
  const Index np = static_cast<Index>(particles.size());
  support.resize(np);
  Index outside = np;  // the first particle outside (the one reported, whatever the threads' timing)
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index p = 0; p < np; ++p) {
    const Vec2& x = particles.x[p];
    if (!grid.contains(x)) {
#pragma omp critical(lagfsi_mpm_outside)
      outside = std::min(outside, p);
      continue;
    }
    evaluate_support(grid, shape.gimp, shape.particles_per_cell, x, support[p]);
  }
  return outside < np ? outside : -1;
}

}  // namespace lagfsi::mpm
