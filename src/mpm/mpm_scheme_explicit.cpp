// Explicit single-phase MPM (mpm_scheme.hpp), after Sulsky, Chen & Schreyer (1994) and the "modified
// Lagrangian" (MUSL) algorithm of Ludeña (2016, ch. 3; Al-Kafaji 2013); one sub-step:
//
//   particles -> grid:  m_I, (m v)_I, f_I (mpm_transfer.cpp)
//   grid update:        v_I <- v_I + dt f_I / m_I (fixed components zeroed; local damping f -= alpha |f| sign(v)),
//                       one step of the shared central difference (time_integrator.hpp) in leapfrog form:
//                       the mapped grid velocity is the half-step velocity v_{n-1/2}, the step is started from
//                       v_n = v_{n-1/2} + dt/2 a_n, a_n = f_I / m_I, and explicit_step_into() hands the force
//                       callback v_{n+1/2} = v_{n-1/2} + dt a_n (equal to (m v + dt f)_I / m_I up to rounding);
//                       the callback does the rest of the sub-step. The force at the sub-step's end is the next
//                       sub-step's mapping on a reset grid, so the callback returns none and the contract's
//                       a_{n+1}, v_{n+1} of the scratch grid state are not used.
//   grid -> particles:  v_p += dt sum_I N_Ip f_I / m_I (FLIP),  x_p += dt sum_I N_Ip v_I
//   stress update:      L_p = sum_I v_I (x) grad N_Ip, F_p = (I + dt L_p) F_p, V_p = det F_p V_p0,
//                       sigma_p += C : dt sym(L_p) (small strain rate; the material's return mapping)
//
// with the grid velocity of the stress update taken, as chosen by "update":
//  - "musl": re-mapped from the updated particle velocities (Ludeña's algorithm; the most robust);
//  - "usl":  the grid velocity of the grid update;
//  - "usf":  the stress is updated first, from the grid velocity of the mapped momentum.
// Damping: Cundall local and Rayleigh (mass-proportional on the grid, stiffness-proportional as a viscous
// stress); the grid forces also take the particle loads and the absorbing and free-field boundaries.
#include "mpm_scheme.hpp"

#include <lagfsi/mpm/mpm_transfer.hpp>

#include <cmath>
#include <stdexcept>

namespace lagfsi::mpm {

namespace {

class ExplicitSinglePhase final : public ExplicitScheme {
 public:
  ExplicitSinglePhase(StressUpdate update, std::unique_ptr<TimeIntegrator> integrator)
      : update_(update), integrator_(std::move(integrator)) {
    if (!integrator_ || !integrator_->is_explicit())
      throw std::invalid_argument("the explicit MPM scheme needs an explicit time integrator");
  }
  double wave_speed(const MpmBody& b) const override { return b.material->p_wave_speed(); }

 protected:
  void substep(MpmBody& b, double dt) override;

 private:
  /// Stress update of every particle from the nodal velocities vgrid (and F, volume, strain, strain rate).
  void stress_update(MpmBody& b, double dt, const std::vector<Vec2>& vgrid) const;

  /// The rest of the sub-step once the grid velocities are v_{n+1/2}: prescribed motion, grid to particles,
  /// the MUSL re-mapping and the stress update.
  void finish_substep(MpmBody& b, double dt);

  StressUpdate update_;
  std::unique_ptr<TimeIntegrator> integrator_;  // central difference: the grid's velocity update
  ScatterBuffers buffers_;                      // per-thread grid copies of the scatter
  KinematicState grid_state_;                   // the sub-step's grid dofs (2 per node; scratch, reset every sub-step)
  Vec no_inverse_mass_, end_force_;  // the end force is not formed (zero inverse mass): see the file's header
};

void ExplicitSinglePhase::stress_update(MpmBody& b, double dt, const std::vector<Vec2>& vgrid) const {
  Particles& P = b.particles;
  const MpmMaterial& mat = *b.material;
  const bool plastic = mat.plastic();
  const Index np = static_cast<Index>(P.size());
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index p = 0; p < np; ++p) {
    const Support& s = b.support[p];
    const Mat2 L = velocity_gradient(vgrid, s);
    P.F[p] = (Mat2::Identity() + dt * L) * P.F[p];
    const Mat2& F = P.F[p];
    P.volume[p] = (F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0)) * P.volume0[p];
    const double dxx = dt * L(0, 0), dyy = dt * L(1, 1), dxy = 0.5 * dt * (L(0, 1) + L(1, 0));
    P.strain_rate[p] = {L(0, 0), L(1, 1), 0.5 * (L(0, 1) + L(1, 0))};  // for the stiffness-proportional damping
    // Jaumann rate: the stress turns with the spin W = (L - L^T)/2, w = W_xy dt.
    const double w = 0.5 * dt * (L(0, 1) - L(1, 0));
    mat.elastic_trial(P.stress[p], {dxx, dyy, dxy, w});
    if (plastic) P.plastic_multiplier[p] += mat.return_mapping(P.stress[p]);
    auto& e = P.strain[p];
    e[0] += dxx;
    e[1] += dyy;
    e[2] += dxy;
  }
}

void ExplicitSinglePhase::substep(MpmBody& b, double dt) {
  Particles& P = b.particles;
  Grid& grid = b.grid;
  const GridBoundaries& bc = b.boundaries;
  const Damping& damping = b.damping;
  const size_t nn = grid.mass.size();
  b.locate_particles();
  const Vec2 g = b.gravity();
  const StiffnessDamping viscous{damping.stiffness, b.material.get()};
  if (update_ == StressUpdate::Usf) {
    particles_to_grid(P, b.support, true, false, g, viscous, grid, buffers_);
    bc.apply_fixed(grid.momentum);
    velocities_from_momentum(grid);
    stress_update(b, dt, grid.velocity);
    particles_to_grid(P, b.support, false, true, g, viscous, grid, buffers_);
  } else {
    particles_to_grid(P, b.support, true, true, g, viscous, grid, buffers_);
    bc.apply_fixed(grid.momentum);
  }
  add_particle_loads(b.loads, b.support, b.t, grid.force);
  // Grid update; local (Cundall) damping opposes the node's motion with a share of its unbalanced force;
  // Rayleigh mass-proportional damping is the force -alpha m_I v_I.
  for (size_t i = 0; i < nn; ++i) {
    if (!(grid.mass[i] > 0)) continue;
    if (damping.mass > 0) grid.force[i] -= damping.mass * grid.momentum[i];
  }
  b.boundaries.add_free_field_tractions(grid, b.t, *b.material, damping.stiffness);
  for (size_t i = 0; i < nn; ++i) {
    if (!(grid.mass[i] > 0)) continue;
    if (damping.local > 0 && b.t < damping.local_until) {
      const Vec2 v = grid.momentum[i] / grid.mass[i];
      for (int c = 0; c < 2; ++c)
        if (v[c] != 0.0) grid.force[i][c] -= damping.local * std::abs(grid.force[i][c]) * (v[c] > 0 ? 1.0 : -1.0);
    }
  }
  bc.apply_fixed(grid.force);
  b.boundaries.add_dashpot_forces(grid, b.t, dt, *b.material);
  b.boundaries.step_free_fields(b.t, dt, *b.material, damping.mass, damping.stiffness);
  bc.apply_fixed(grid.force);
  // The grid update through the time integrator (see the header): a_n = f / m, v_n = v_{n-1/2} + dt/2 a_n at
  // the nodes with mass; the grid velocity of the other nodes is left as it is (as the momentum update did).
  const Index nd = 2 * static_cast<Index>(nn);
  KinematicState& s = grid_state_;
  s.t = b.t;
  s.x.setZero(nd);
  s.v.resize(nd);
  s.a.resize(nd);
  for (size_t i = 0; i < nn; ++i)
    for (int c = 0; c < 2; ++c) {
      const Index d = 2 * static_cast<Index>(i) + c;
      if (grid.mass[i] > 0) {
        s.a[d] = grid.force[i][c] / grid.mass[i];
        s.v[d] = grid.momentum[i][c] / grid.mass[i] + 0.5 * dt * s.a[d];
      } else {
        s.a[d] = s.v[d] = 0.0;
      }
    }
  if (no_inverse_mass_.size() != nd) no_inverse_mass_ = Vec::Zero(nd);
  integrator_->explicit_step_into(
      [&](const Vec&, const Vec& v_half, double, Vec& f) {
        for (size_t i = 0; i < nn; ++i) {
          if (!(grid.mass[i] > 0)) continue;
          grid.velocity[i] = v_half.segment<2>(2 * static_cast<Index>(i));
          grid.momentum[i] = grid.mass[i] * grid.velocity[i];
        }
        finish_substep(b, dt);
        f.setZero();
      },
      no_inverse_mass_, dt, s, end_force_);
}

void ExplicitSinglePhase::finish_substep(MpmBody& b, double dt) {
  Particles& P = b.particles;
  Grid& grid = b.grid;
  const GridBoundaries& bc = b.boundaries;
  const Index np = static_cast<Index>(P.size());
  const Vec2 g = b.gravity();
  const StiffnessDamping viscous{b.damping.stiffness, b.material.get()};
  bc.apply_fixed(grid.velocity);
  // Prescribed motion: the node's velocity at the end of the sub-step; its force is what that takes.
  bc.impose_motion(grid, b.t + dt, dt);
  // Grid to particles: FLIP velocity, positions with the grid velocity.
  b.gravity_work += grid_to_particles(grid, b.support, dt, b.flip, g, P);
  if (update_ == StressUpdate::Musl) {
    particles_to_grid(P, b.support, true, false, g, viscous, grid, buffers_);
    velocities_from_momentum(grid);
    bc.apply_fixed(grid.velocity);
    for (const auto& m : bc.moving) grid.velocity[m.node][m.comp] = m.velocity(b.t + dt);
  }
  if (update_ != StressUpdate::Usf) stress_update(b, dt, grid.velocity);
  for (Index p = 0; p < np; ++p)
    if (!(P.volume[p] > 0) || !std::isfinite(P.stress[p][1])) throw b.particle_error(p, "inverted or non-finite");
}

}  // namespace

std::unique_ptr<ExplicitScheme> make_explicit_scheme(StressUpdate update, std::unique_ptr<TimeIntegrator> integrator) {
  return std::make_unique<ExplicitSinglePhase>(update, std::move(integrator));
}

}  // namespace lagfsi::mpm
