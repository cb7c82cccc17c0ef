#pragma once
/// @file mpm/mpm_transfer.hpp
/// Transfers between the particles and the grid of a single-phase body (Sulsky, Chen & Schreyer 1994):
///
///   particles -> grid:  m_I = sum_p N_Ip m_p,  (m v)_I = sum_p N_Ip m_p v_p,
///                       f_I = sum_p [ -V_p sigma_p . grad N_Ip + N_Ip m_p g ]
///   grid -> particles:  v_p += dt sum_I N_Ip f_I / m_I (FLIP),  x_p += dt sum_I N_Ip v_I
///   velocity gradient:  L_p = sum_I v_I (x) grad N_Ip
#include <lagfsi/mpm/mpm_material.hpp>
#include <lagfsi/mpm/mpm_state.hpp>

#include <vector>

namespace lagfsi::mpm {

/// Per-thread copies of the grid arrays of the parallel scatter (kept between calls).
struct ScatterBuffers {
  std::vector<std::vector<double>> mass;
  std::vector<std::vector<Vec2>> momentum, force;
};

/// Rayleigh stiffness-proportional damping in the internal force: the viscous stress beta C : D of the
/// particle's last strain rate D, C the material's elastic stiffness (beta = 0: none).
struct StiffnessDamping {
  double beta = 0;
  const MpmMaterial* material = nullptr;
};

/// Particles to grid: with `momentum`, grid.mass and grid.momentum; with `force`, grid.force (internal force
/// of the stress, plus the viscous stress of `damping`, and gravity g). Each array it writes is overwritten at
/// every node. In parallel for 20000 particles or more: each thread accumulates into its own copy of the
/// arrays (a particle's nodes are shared with its neighbours', so a direct parallel scatter would race).
void particles_to_grid(const Particles& particles, const std::vector<Support>& support, bool momentum, bool force,
                       const Vec2& g, const StiffnessDamping& damping, Grid& grid, ScatterBuffers& buffers);

/// v_I = (m v)_I / m_I at the nodes with mass, zero elsewhere.
void velocities_from_momentum(Grid& grid);

/// Grid to particles after the grid update (grid.force the nodes' forces, grid.velocity their new velocities):
/// a_p = sum_I N_Ip f_I / m_I, v_p = flip (v_p + dt a_p) + (1 - flip) sum_I N_Ip v_I (1: FLIP, 0: PIC),
/// x_p += dt sum_I N_Ip v_I; nodes without mass are skipped. Returns the work of gravity sum_p m_p g . dx_p.
double grid_to_particles(const Grid& grid, const std::vector<Support>& support, double dt, double flip, const Vec2& g,
                         Particles& particles);

/// Velocity gradient at a particle, L = sum_I v_I (x) grad N_Ip, from nodal velocities v.
inline Mat2 velocity_gradient(const std::vector<Vec2>& v, const Support& s) {
  Mat2 L = Mat2::Zero();
  for (int k = 0; k < s.n; ++k) L += v[s.node[k]] * s.dN[k].transpose();
  return L;
}

}  // namespace lagfsi::mpm
