// Particle-grid transfers of a single-phase MPM body (src/mpm/include/lagfsi/mpm/mpm_transfer.hpp), after Sulsky,
// Chen & Schreyer (1994):
//   particles -> grid:  m_I = sum_p N_Ip m_p,  (m v)_I = sum_p N_Ip m_p v_p,
//                       f_I = sum_p [ -V_p sigma_p . grad N_Ip + N_Ip m_p g ]
//   grid -> particles:  v_p += dt sum_I N_Ip f_I / m_I (FLIP),  x_p += dt sum_I N_Ip v_I
#include <lagfsi/mpm/mpm_transfer.hpp>
#include <lagfsi/parallel_sum.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace lagfsi::mpm {

void particles_to_grid(const Particles& P, const std::vector<Support>& support, bool momentum, bool force,
                       const Vec2& g, const StiffnessDamping& damping, Grid& grid, ScatterBuffers& buffers) {
  // Particles to grid, in parallel: each thread accumulates its share of the particles into its own copy of
  // the grid arrays, then the copies are summed node by node in thread order (a particle's nodes are shared
  // with its neighbours', so a direct parallel scatter would race, and atomic additions would add in a different
  // order from run to run; parallel_sum.hpp).
  const Index np = static_cast<Index>(P.size());
  const Index nn = static_cast<Index>(grid.mass.size());
  const double beta = damping.beta;
  const double lambda = damping.material ? damping.material->lame_lambda() : 0.0;
  const double mu = damping.material ? damping.material->shear_modulus() : 0.0;
  int nt = 1;
#ifdef _OPENMP
  nt = np >= 20000 ? omp_get_max_threads() : 1;
#endif
  auto& tm = buffers.mass;
  auto& tp = buffers.momentum;
  auto& tf = buffers.force;
  if (static_cast<int>(tm.size()) != nt) {
    tm.assign(nt, {});
    tp.assign(nt, {});
    tf.assign(nt, {});
  }
#pragma omp parallel num_threads(nt)
  {
    int tid = 0;
#ifdef _OPENMP
    tid = omp_get_thread_num();
#endif
    auto& m = tm[tid];
    auto& mv = tp[tid];
    auto& f = tf[tid];
    if (momentum) {
      m.assign(nn, 0.0);
      mv.assign(nn, Vec2::Zero());
    }
    if (force) f.assign(nn, Vec2::Zero());
#pragma omp for schedule(static)
    for (Index p = 0; p < np; ++p) {
      const Support& sp = support[p];
      const double mp = P.mass[p];
      const Vec2 mvp = mp * P.v[p];
      Stress sg = P.stress[p];
      if (beta > 0) {  // Rayleigh stiffness-proportional damping: the viscous stress beta C : D
        const auto& r = P.strain_rate[p];
        const double tr = r[0] + r[1];
        sg[0] += beta * (lambda * tr + 2 * mu * r[0]);
        sg[1] += beta * (lambda * tr + 2 * mu * r[1]);
        sg[2] += beta * 2 * mu * r[2];
      }
      const double V = P.volume[p];
      for (int k = 0; k < sp.n; ++k) {
        const Index I = sp.node[k];
        if (momentum) {
          m[I] += sp.N[k] * mp;
          mv[I] += sp.N[k] * mvp;
        }
        if (force) {
          const Vec2& d = sp.dN[k];
          f[I] += sp.N[k] * mp * g - V * Vec2(sg[0] * d.x() + sg[2] * d.y(), sg[2] * d.x() + sg[1] * d.y());
        }
      }
    }
#pragma omp for schedule(static)
    for (Index I = 0; I < nn; ++I) {
      if (momentum) {
        double a = 0;
        Vec2 b = Vec2::Zero();
        for (int t = 0; t < nt; ++t) {
          a += tm[t][I];
          b += tp[t][I];
        }
        grid.mass[I] = a;
        grid.momentum[I] = b;
      }
      if (force) {
        Vec2 c = Vec2::Zero();
        for (int t = 0; t < nt; ++t) c += tf[t][I];
        grid.force[I] = c;
      }
    }
  }
}

void velocities_from_momentum(Grid& grid) {
  const size_t nn = grid.mass.size();
  for (size_t i = 0; i < nn; ++i)
    grid.velocity[i] = grid.mass[i] > 0 ? Vec2(grid.momentum[i] / grid.mass[i]) : Vec2::Zero();
}

double grid_to_particles(const Grid& grid, const std::vector<Support>& support, double dt, double flip, const Vec2& g,
                         Particles& P) {
  // Grid to particles: FLIP velocity, positions with the grid velocity. The work of gravity is summed per
  // thread and added in thread order (parallel_sum.hpp): the same in every run with the same threads.
  const Index np = static_cast<Index>(P.size());
  ThreadSums<> work;
#pragma omp parallel if (np >= 20000)
  {
    double gw = 0;
#pragma omp for schedule(static) nowait
    for (Index p = 0; p < np; ++p) {
      const Support& s = support[p];
      Vec2 a = Vec2::Zero(), v = Vec2::Zero();
      for (int k = 0; k < s.n; ++k) {
        const Index I = s.node[k];
        if (!(grid.mass[I] > 0)) continue;
        a += s.N[k] * grid.force[I] / grid.mass[I];
        v += s.N[k] * grid.velocity[I];
      }
      P.v[p] = flip * (P.v[p] + dt * a) + (1.0 - flip) * v;
      P.acceleration[p] = a;
      const Vec2 dx = dt * v;
      P.x[p] += dx;
      gw += P.mass[p] * g.dot(dx);
    }
    work.mine()[0] = gw;
  }
  return work.total();
}

}  // namespace lagfsi::mpm
