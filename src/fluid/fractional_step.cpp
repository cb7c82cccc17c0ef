// PFEM fluid, scheme "fractional_step": an incremental pressure-correction (projection) step of Chorin
// (1968) and Goda (1979) on the particles' mesh at the start of the step (x_n, after remeshing), as used in
// PFEM by Idelsohn, Oñate & Del Pin (2004, Int. J. Numer. Meth. Eng. 61:964), with P1 velocity and pressure and
// lumped mass m_a = sum_e rho A_e / 3. Pressures p (positive in compression), per step:
//
//  1. predictor   m_a (u*_a - u^n_a) / dt = m_a g + sum_e A_e pbar^n_e grad N_a - sum_e mu A_e (L + L^T) grad N_a
//                 with the viscous term at u^n (explicit) or its Laplacian part at u* (implicit: one symmetric
//                 positive definite scalar system for both components); wall particles take the wall's
//                 velocity; a particle sliding on a no-slip wall ("wall_friction": "navier") feels
//                 -k (u*_t - v_wall,t) (fluid_walls.hpp), implicitly in both variants.
//  2. pressure    (dt / rho) L dp + C dp = - sum_e (A_e / 3)(r_e + c_vol) + owed_a / T,   dp = p^{n+1} - p^n,
//                 r_e = div u* + dt det(grad u*) the exact area rate of the element moved by dt u* (P1; with the
//                 advected and level-set detections, div u* alone with the alpha shape),
//                 L_ab = sum_e A_e grad N_a . grad N_b (the Laplacian replaces D M^-1 G: the stabilization
//                 of equal-order interpolation, Codina 2001), C = diag((A/3) / (K dt)) the slight
//                 compressibility, dp = 0 on the free surface (p = 0 there) and a natural condition on walls.
//  3. correction  u^{n+1}_a = u*_a + (dt / m_a) sum_e A_e dpbar_e grad N_a,   x^{n+1} = x^n + dt u^{n+1}
//                 (symplectic Euler: the position update uses the new velocity, which keeps an undamped
//                 oscillation bounded where x^n + dt (u^n + u^{n+1}) / 2 would make it grow).
//
// With "mass": "consistent" the predictor's m_a becomes the consistent P1 mass matrix, M_ab = sum_e rho A_e
// (1 + delta_ab) / 12, in the elements inside the water (assemble_mass says which keep the lumped mass, rho A_e / 3
// on the diagonal): one scalar matrix for both components, solved by conjugate gradients with its diagonal as
// preconditioner (M is spectrally equivalent to it: the iterations do not grow with the mesh). Its rows sum to the
// lumped masses, so gravity m_a g is M g and the hydrostatic state stays a fixed point. The correction keeps the
// lumped mass, for which the pressure equation's Laplacian stands in for D M^-1 G. The lumped predictor smooths the
// pressure's force over each particle's elements, which damps resolved vortices (docs/decisions/0021).
//
// The hydrostatic state is a fixed point: with u = 0 and p linear in depth, pbar terms balance m g exactly
// at every particle (one-point quadrature of the linear p is exact and the mass is lumped), so div u* = 0
// and dp = 0. A step costs one CHOLMOD factorization of a scalar Laplacian (and, with the implicit viscous
// predictor, one more of a scalar matrix of the same pattern) instead of the monolithic scheme's Newton
// iterations on (x, y, p) (pspg_scheme.cpp).
#include "element_loop.hpp"
#include "fluid_scheme.hpp"
#include "fractional_step_reactions.hpp"
#include "masked_cg.hpp"

#include <lagfsi/assembly.hpp>
#include <lagfsi/linear_solver_input.hpp>
#include <lagfsi/parallel_sum.hpp>
#include <lagfsi/system_assembly.hpp>
#include <lagfsi/time_integrator.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

namespace lagfsi::fluid {

namespace {
/// Rows and columns of the prescribed unknowns (fixed(i)) become those of the identity; `diag(i)` is added to
/// the diagonal of the others.
template <class Fixed, class Diag>
void constrain(SparseMatrix& A, const Fixed& fixed, const Diag& diag) {
  dirichlet_identity(A, fixed, [&](Index row, Index col, double& value) {
    if (row == col) value += diag(row);
  });
}

/// The viscous predictor's solver: the Poisson's settings for a mass matrix plus dt times a viscous stiffness.
LinearSolverSettings viscous(const FractionalStepSettings& s) {
  LinearSolverSettings v = s.solver;
  v.kind = SystemKind::mass_dominated;
  return v;
}

/// The fractional step: the pressure Poisson matrix and the implicit viscous predictor's matrix (both one dof
/// per particle, one pattern) on the step's mesh, and the step's new velocities.
class FractionalStep final : public FluidScheme {
 public:
  FractionalStep(const FluidParts& f, const FractionalStepSettings& s)
      : FluidScheme(f), s_(s), solver_(make_linear_solver(s.solver)), viscous_solver_(make_linear_solver(viscous(s))) {}
  void begin_step() override {
    const Index np = f_.cloud.n();
    // Over several processes with a distributed solver, each assembles the elements with a particle in its rows
    // (mpi_run.hpp), on the pattern of those elements alone, and the particles' forces are combined over the
    // processes.
    rows_.set(s_.solver.distributed, np);
    SparseMatrix().swap(viscous_);  // let go before the new pattern is built
    rows_.renew_pattern(poisson_pattern_, poisson_, f_.mesh.tri, f_.mesh.conn, np, 1);
    if (viscous_implicit()) viscous_ = poisson_;
    if (s_.consistent_mass) mass_ = poisson_;
    // A new mesh: new matrices. Re-solves of the step (a coupling pass) keep the factorizations, which
    // depend on the mesh only.
    step_factorized_ = false;
  }
  /// The whole step.
  IterationReport iterate() override;
  void end_step() override {
    inverted_kept_ += inverted_in_step_;
    inverted_in_step_ = 0;
    KinematicState& s = f_.cloud.state();
    s.a = (v_new_ - s.v) / f_.step.dt;
    s.v = v_new_;
    s.x = f_.step.x;
  }
  Json linear_solvers() const override {
    Json j = {{"pressure", solver_summary(*solver_)}};
    if (viscous_solver_->statistics().setups > 0) j["viscous"] = solver_summary(*viscous_solver_);
    return j;
  }
  /// v_{n+1}.
  Vec step_velocity() const override { return v_new_; }
  long inverted_kept() const override { return inverted_kept_; }
  void serialize(StateArchive& ar) override { ar.io(inverted_kept_); }

 private:
  /// What the stages of a step share: the step mesh's element areas and shape-function gradients, the lumped
  /// masses, the prescribed velocity components (vfixed, their values in ustar) and the walls' friction, the
  /// predictor's explicit forces, the pressure increment dp and its force du.
  struct Work {
    std::vector<double> area;
    std::vector<std::array<Vec2, 3>> grad;
    Vec mass, ustar, friction, friction_force, force, dp, du;
    std::vector<char> vfixed;
    bool implicit = false;
  };
  /// The stages of a step: the mesh's geometry and masses, the prescribed velocities, the predictor u*, the
  /// pressure increment, the correction u^{n+1} with the forces of the prescribed particles, and the new
  /// positions with their checks and the step's report.
  void geometry(Work& wk);
  void prescribe_velocities(Work& wk);
  void predict_velocities(Work& wk);
  void pressure_increment(Work& wk);
  void correct(Work& wk);
  IterationReport move_and_check(Work& wk);
  /// "mass": "consistent": the step mesh's consistent mass matrix into mass_ (once per mesh).
  void assemble_mass(const Work& wk);
  /// The mass times d (2 np, both components): m_a d_a lumped, M d consistent.
  Vec mass_times(const Work& wk, const Vec& d, bool consistent) const;
  /// The viscous predictor is implicit (the automatic choice: when the explicit one would exceed its
  /// stability limit dt <= rho h_min^2 / (8 mu), h_min = 0.3 h).
  bool viscous_implicit() const;
  /// Factorizes a matrix of the step (time counted as factorization); a failure names the body and `what`.
  void factorize_step_matrix(LinearSolver& solver, const SparseMatrix& A, const char* what);

  FractionalStepSettings s_;
  std::unique_ptr<LinearSolver> solver_, viscous_solver_;
  ProcessRows rows_;  // the particles whose rows this process fills (the element assembly divided among processes)
  ElementPattern poisson_pattern_;
  SparseMatrix poisson_, viscous_, viscous_stiffness_, mass_;
  Vec v_new_;
  ThreadScatter scatter_;                          // the element loops' per-thread sums
  bool step_factorized_ = false;                   // the step's matrices are factorized (reused by re-solves)
  long inverted_in_step_ = 0, inverted_kept_ = 0;  // inverted elements in the last solve / in the accepted
                                                   // steps ("inverted_elements": "remesh")
};

void FractionalStep::factorize_step_matrix(LinearSolver& solver, const SparseMatrix& A, const char* what) {
  const auto t0 = SteadyClock::now();
  try {
    solver.setup(A);
  } catch (const SolverError& err) {
    throw SolverError("body '" + f_.c.name + "': " + what + ": " + err.what());
  }
  f_.times.factorization += seconds_since(t0);
}

bool FractionalStep::viscous_implicit() const {
  if (s_.viscous_step != "automatic") return s_.viscous_step == "implicit";
  if (f_.c.mu <= 0) return false;
  const double hmin = 0.3 * f_.c.h;
  const double dt = f_.step.dt;
  return dt > f_.c.rho * hmin * hmin / (8.0 * f_.c.mu);
}

IterationReport FractionalStep::iterate() {
  Work wk;
  const auto t0 = SteadyClock::now();
  geometry(wk);
  prescribe_velocities(wk);
  if (s_.consistent_mass && !step_factorized_) assemble_mass(wk);
  f_.times.assembly += seconds_since(t0);
  predict_velocities(wk);
  pressure_increment(wk);
  correct(wk);
  return move_and_check(wk);
}

void FractionalStep::geometry(Work& wk) {
  const Index np = f_.cloud.n();
  const Index ne = f_.mesh.num_elements();
  const double dt = f_.step.dt;
  const Vec& x = f_.cloud.x();
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  // Geometry of the step's mesh and lumped masses.
  wk.area.assign(ne, 0.0);
  wk.grad.assign(ne, {});
  wk.mass = Vec::Zero(np);
  Index inverted = ne;  // the lowest inverted element (the one reported, whatever the threads' timing)
  element_loop(ne, scatter_, {values_of(wk.mass)}, [&](Index e, std::span<double* const> out) {
    const auto& t = tri[e];
    const Vec2 a = x.segment<2>(2 * t[0]), b = x.segment<2>(2 * t[1]), c = x.segment<2>(2 * t[2]);
    const double A2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (!(A2 > 0.0)) {
#pragma omp critical(lagfsi_fs_inverted)
      inverted = std::min(inverted, e);
      return;
    }
    wk.area[e] = 0.5 * A2;
    for (int k = 0; k < 3; ++k) {
      const Vec2& p = x.segment<2>(2 * t[(k + 1) % 3]);
      const Vec2& q = x.segment<2>(2 * t[(k + 2) % 3]);
      wk.grad[e][k] = Vec2(p.y() - q.y(), q.x() - p.x()) / A2;
    }
    for (Index i : t) out[0][i] += f_.c.rho * wk.area[e] / 3.0;
  });
  if (inverted < ne) {
    const auto& t = tri[inverted];
    throw SolverError("body '" + f_.c.name + "': element " + std::to_string(inverted) + " (particles " +
                      std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) +
                      ") is inverted at t = " + std::to_string(f_.step.t_new - dt));
  }
}

void FractionalStep::assemble_mass(const Work& wk) {
  const Index ne = f_.mesh.num_elements();
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  const std::vector<char>& fixed = f_.step.fixed;
  // The elements with a particle whose pressure is prescribed (the free surface, an outlet: p = 0) or that slides on a
  // wall as a constraint keep the lumped mass (their rows still sum to the particles' masses); wall and ghost
  // particles do not (a channel's wake is made at its walls). With the consistent mass at the free surface, a dam
  // break's splash gained energy until an element turned over; at the particles sliding on its walls, its water
  // drifted (docs/decisions/0021).
  const std::vector<ParticleKind>& kind = f_.cloud.kind();
  const auto inside = [&](Index i) {
    const bool sliding = kind[i] == ParticleKind::Fluid && (wk.vfixed[2 * i] || wk.vfixed[2 * i + 1] ||
                                                            wk.friction[2 * i] > 0 || wk.friction[2 * i + 1] > 0);
    return fixed[3 * i + 2] == 0 && wk.mass[i] > 0 && !sliding;
  };
  double* mv = mass_.valuePtr();
  std::fill(mv, mv + mass_.nonZeros(), 0.0);
  element_loop(ne, scatter_, {values_of(mass_)}, [&](Index e, std::span<double* const> out) {
    const auto& t = tri[e];
    const int* sc = poisson_pattern_.scatter(e);
    const double m = f_.c.rho * wk.area[e] / 12.0;
    const bool consistent = inside(t[0]) && inside(t[1]) && inside(t[2]);
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a)
        if (consistent)
          out[0][sc[b * 3 + a]] += a == b ? 2.0 * m : m;
        else if (a == b)
          out[0][sc[b * 3 + a]] += 4.0 * m;
  });
}

Vec FractionalStep::mass_times(const Work& wk, const Vec& d, bool consistent) const {
  const Index np = f_.cloud.n();
  Vec out(2 * np);
  if (!consistent) {
    for (Index k = 0; k < 2 * np; ++k) out[k] = wk.mass[k / 2] * d[k];
    return out;
  }
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> dc(d.data(), np, 2);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> oc(out.data(), np, 2);
  oc = mass_ * dc;
  return out;
}

void FractionalStep::prescribe_velocities(Work& wk) {
  const Index np = f_.cloud.n();
  const double dt = f_.step.dt;
  const Vec2 g = f_.c.gravity;
  const Vec& x = f_.cloud.x();
  const Vec& v = f_.cloud.v();
  const std::vector<ParticleKind>& kind = f_.cloud.kind();
  // Velocity components that are prescribed: wall particles (the wall's velocity), slip
  // constraints of fixed meshes (zero), fluid particles in no element (ballistic).
  wk.vfixed.assign(2 * np, 0);
  wk.ustar = v;
  for (Index i = 0; i < np; ++i) {
    if (kind[i] != ParticleKind::Fluid) {
      wk.vfixed[2 * i] = wk.vfixed[2 * i + 1] = 1;
      wk.ustar.segment<2>(2 * i) = Vec2::Zero();
    } else if (!(wk.mass[i] > 0)) {
      wk.vfixed[2 * i] = wk.vfixed[2 * i + 1] = 1;
      wk.ustar.segment<2>(2 * i) = v.segment<2>(2 * i) + dt * g;
    }
  }
  {  // the boundaries' own particles (moving walls'): the prescribed velocity at the end of the step
    Vec a_own = Vec::Zero(2 * np);
    f_.boundaries.move_own(f_.step.t_new, wk.ustar, a_own);
  }
  for (const auto& k : f_.boundaries.constraints()) {  // particles on walls: the wall's velocity component
    wk.vfixed[2 * k.i + k.c] = 1;
    wk.ustar[2 * k.i + k.c] = f_.boundaries.velocity(k, f_.step.t_new);
  }
  // No-slip walls with "navier" friction (fluid_walls.hpp): the force -k (u*_t - v_wall,t) on the free
  // tangential component of a particle on one, taken at u* (implicit: unconditionally stable). The walls
  // are horizontal or vertical here (FluidScheme::wall_frames), so the component is x or y.
  wk.friction = Vec::Zero(2 * np);
  wk.friction_force = Vec::Zero(2 * np);  // k, k v_wall,t per component
  for (const BoundaryFriction& w : f_.boundaries.frictions()) {
    const Index dof = 2 * w.i + w.c;
    if (wk.vfixed[dof]) continue;
    wk.friction[dof] = f_.boundaries.friction_coefficient(w);
    wk.friction_force[dof] = wk.friction[dof] * f_.boundaries.friction_velocity(w, f_.step.t_new);
  }
  // Ghost particles: the mean velocity of the structure's boundary over the step, (x_new{n+1} - x_n)/dt. The
  // fluid particles move by dt u^{n+1}, so this is the velocity whose divergence-free field keeps the
  // step's mesh motion consistent with the boundary's; the structure's own v_{n+1} (trapezoidal rule)
  // alternates around it after a sudden load and would pump pressure spikes into the fluid.
  for (size_t gi = 0; gi < f_.ghosts.count() && f_.ghosts.x().size() > 0; ++gi)
    if (!f_.ghosts.merged(gi)) {
      const Index i = f_.ghosts.index(gi);
      wk.ustar.segment<2>(2 * i) = (f_.ghosts.x().segment<2>(2 * gi) - x.segment<2>(2 * i)) / dt;
    }
}

void FractionalStep::predict_velocities(Work& wk) {
  const Index np = f_.cloud.n();
  const Index ne = f_.mesh.num_elements();
  const double dt = f_.step.dt;
  const Vec2 g = f_.c.gravity;
  const Vec& v = f_.cloud.v();
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  Vec& pres = f_.cloud.p();
  auto t0 = SteadyClock::now();
  // 1. Predictor: gravity, the pressure of the last step and the viscous force. Explicit: all of
  // mu A (L + L^T) grad N_a at u^n. Implicit: the Laplacian part mu A (grad N_a . grad N_b) u_b at u*
  // (the stiff part, one scalar matrix for both components) and the transposed part mu A L^T grad N_a
  // at u^n (it vanishes for a divergence-free field; keeping it explicit keeps the stress symmetric).
  wk.implicit = viscous_implicit();
  wk.force = Vec::Zero(2 * np);
  element_loop(ne, scatter_, {values_of(wk.force)}, [&](Index e, std::span<double* const> out) {
    if (!rows_.mine(tri[e])) return;
    const auto& t = tri[e];
    const double pbar = (pres[t[0]] + pres[t[1]] + pres[t[2]]) / 3.0;
    Mat2 L = Mat2::Zero();
    if (f_.c.mu > 0 && !f_.boundaries.inviscid(tri[e]))
      for (int k = 0; k < 3; ++k) L += v.segment<2>(2 * t[k]) * wk.grad[e][k].transpose();
    const Mat2 visc = wk.implicit ? Mat2(L.transpose()) : Mat2(L + L.transpose());
    for (int a = 0; a < 3; ++a) {
      const Vec2 f = wk.area[e] * (pbar * wk.grad[e][a] - f_.c.mu * visc * wk.grad[e][a]);
      out[0][2 * t[a]] += f.x();
      out[0][2 * t[a] + 1] += f.y();
    }
  });
  rows_.combine(wk.force, 2);
  for (Index i = 0; i < np; ++i) wk.force.segment<2>(2 * i) += wk.mass[i] * g;
  f_.times.assembly += seconds_since(t0);

  if (!wk.implicit && s_.consistent_mass) {
    // Per component c: (M / dt + k) u*_c = M u^n_c / dt + f_c + k v_wall, the prescribed components given.
    t0 = SteadyClock::now();
    const Vec Mv = mass_times(wk, v, true);
    for (int c = 0; c < 2; ++c) {
      Vec k(np), rhs(np), y(np);
      std::vector<char> prescribed(static_cast<size_t>(np));
      for (Index i = 0; i < np; ++i) {
        k[i] = dt * wk.friction[2 * i + c];
        rhs[i] = Mv[2 * i + c] + dt * (wk.force[2 * i + c] + wk.friction_force[2 * i + c]);
        y[i] = wk.ustar[2 * i + c];
        prescribed[static_cast<size_t>(i)] = wk.vfixed[2 * i + c];
      }
      masked_jacobi_cg(mass_, k, prescribed, rhs, y);
      for (Index i = 0; i < np; ++i) wk.ustar[2 * i + c] = y[i];
    }
    f_.times.solve += seconds_since(t0);
  } else if (!wk.implicit) {
    for (Index k = 0; k < 2 * np; ++k) {
      if (wk.vfixed[k]) continue;
      const double m = wk.mass[k / 2];
      wk.ustar[k] = wk.friction[k] == 0
                        ? v[k] + dt * wk.force[k] / m
                        : (m * v[k] / dt + wk.force[k] + wk.friction_force[k]) / (m / dt + wk.friction[k]);
    }
  } else {
    // Per component c: (M / dt + K) u*_c = M u^n_c / dt + f_c, K_ab = sum_e mu A grad N_a . grad N_b, the
    // prescribed components eliminated (symmetric positive definite), the wall friction k on the diagonal
    // of its component. Both components share the matrix unless a wall constrains one component only
    // (slip walls, a fixed mesh's or the constraints') or a friction acts on one, then each gets its own.
    const Vec Mv = mass_times(wk, v, s_.consistent_mass);  // M u^n (lumped: m_a u^n_a)
    bool same = true;
    for (Index i = 0; i < np && same; ++i)
      same = wk.vfixed[2 * i] == wk.vfixed[2 * i + 1] && wk.friction[2 * i] == wk.friction[2 * i + 1];
    for (int c = 0; c < 2; ++c) {
      // The matrix depends on the step's mesh only: a re-solve of the step (a coupling pass) reuses it.
      if ((c == 0 && !step_factorized_) || !same) {
        t0 = SteadyClock::now();
        double* kv = viscous_.valuePtr();
        std::fill(kv, kv + viscous_.nonZeros(), 0.0);
        element_loop(ne, scatter_, {values_of(viscous_)}, [&](Index e, std::span<double* const> out) {
          if (!rows_.mine(tri[e]) || f_.boundaries.inviscid(tri[e])) return;
          const int* sc = poisson_pattern_.scatter(e);
          for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a)
              out[0][sc[b * 3 + a]] += f_.c.mu * wk.area[e] * wk.grad[e][a].dot(wk.grad[e][b]);
        });
        if (s_.consistent_mass) {  // M / dt (the same pattern: both copies of the Poisson matrix's)
          const double* mv = mass_.valuePtr();
          for (Index n = 0; n < viscous_.nonZeros(); ++n) kv[n] += mv[n] / dt;
        }
        viscous_stiffness_ = viscous_;  // kept for the elimination of prescribed values below
        constrain(
            viscous_, [&](Index i) { return wk.vfixed[2 * i + c] != 0; },
            [&](Index i) { return (s_.consistent_mass ? 0.0 : wk.mass[i] / dt) + wk.friction[2 * i + c]; });
        f_.times.assembly += seconds_since(t0);
        factorize_step_matrix(*viscous_solver_, viscous_, "viscous predictor");
      }
      t0 = SteadyClock::now();
      Vec known = Vec::Zero(np), rhs(np);
      for (Index i = 0; i < np; ++i)
        if (wk.vfixed[2 * i + c]) known[i] = wk.ustar[2 * i + c];
      const Vec moved = viscous_stiffness_ * known;
      for (Index i = 0; i < np; ++i)
        rhs[i] = wk.vfixed[2 * i + c]
                     ? wk.ustar[2 * i + c]
                     : Mv[2 * i + c] / dt + wk.force[2 * i + c] + wk.friction_force[2 * i + c] - moved[i];
      Vec u;
      viscous_solver_->solve(rhs, u);
      for (Index i = 0; i < np; ++i)
        if (!wk.vfixed[2 * i + c]) wk.ustar[2 * i + c] = u[i];
      f_.times.solve += seconds_since(t0);
    }
  }
}

void FractionalStep::pressure_increment(Work& wk) {
  const Index np = f_.cloud.n();
  const Index ne = f_.mesh.num_elements();
  const double dt = f_.step.dt;
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  const std::vector<char>& fixed = f_.step.fixed;
  // 2. Pressure increment (the matrix, like the viscous one, only once per step's mesh).
  auto t0 = SteadyClock::now();
  const bool assemble = !step_factorized_;
  double* lv = poisson_.valuePtr();
  if (assemble) std::fill(lv, lv + poisson_.nonZeros(), 0.0);
  Vec rhs = Vec::Zero(np), comp = Vec::Zero(np);
  std::vector<std::span<double>> pressure_sums{values_of(rhs)};
  if (assemble) pressure_sums.insert(pressure_sums.end(), {values_of(comp), values_of(poisson_)});
  const std::vector<ParticleKind>& kind = f_.cloud.kind();
  element_loop(ne, scatter_, std::move(pressure_sums), [&](Index e, std::span<double* const> out) {
    if (!rows_.mine(tri[e])) return;
    const auto& t = tri[e];
    // The continuity as the element's exact area rate over the step at u*: with x + dt u the area changes by
    // dt A (div u + dt det(grad u)) exactly (P1, grad u constant), so div u* alone leaves a second-order change in
    // every element (a stretching flow loses area, a rotating one gains). Used with the advected and level-set
    // detections (with the alpha shape the remesh re-detects and corrects the area); an element the step deforms
    // by a tenth or more, or one with a wall particle (an impact: the second order is no guide there), keeps
    // div u*.
    double div = f_.volume.c_vol();
    if (s_.exact_area_rate && kind[t[0]] == ParticleKind::Fluid && kind[t[1]] == ParticleKind::Fluid &&
        kind[t[2]] == ParticleKind::Fluid) {
      Mat2 G = Mat2::Zero();  // grad u*
      for (int k = 0; k < 3; ++k) G += wk.ustar.segment<2>(2 * t[k]) * wk.grad[e][k].transpose();
      const bool small = std::abs(dt * G.trace()) < 0.1 && std::abs(dt * dt * G.determinant()) < 0.1;
      div += small ? G.trace() + dt * G.determinant() : G.trace();
    } else {
      for (int k = 0; k < 3; ++k) div += wk.ustar.segment<2>(2 * t[k]).dot(wk.grad[e][k]);
    }
    const int* sc = poisson_pattern_.scatter(e);
    for (int a = 0; a < 3; ++a) {
      out[0][t[a]] += -wk.area[e] / 3.0 * div;
      if (!assemble) continue;
      if (f_.c.bulk > 0) out[1][t[a]] += wk.area[e] / 3.0 / (f_.c.bulk * dt);
      for (int b = 0; b < 3; ++b)
        out[2][sc[b * 3 + a]] += dt / f_.c.rho * wk.area[e] * wk.grad[e][a].dot(wk.grad[e][b]);
    }
  });
  rows_.combine(rhs, 1);
  // Unknown pressures: connected particles off the free surface (step.fixed from FluidModel::set_dirichlet); the others
  // keep p = 0 (set in predict), so their increment is zero and their columns drop out.
  if (assemble)
    constrain(
        poisson_, [&](Index i) { return fixed[3 * i + 2] != 0; }, [&](Index i) { return comp[i]; });
  // With particle volumes the rows return what their particles are owed, owed / T (the free-surface particles,
  // which have none, return theirs by moves: VolumeCorrection::return_owed_by_moves).
  for (Index i = 0; i < np; ++i)
    if (fixed[3 * i + 2])
      rhs[i] = 0.0;
    else if (wk.mass[i] > 0)
      rhs[i] += f_.volume.owed_rate(i);
  f_.times.assembly += seconds_since(t0);
  if (assemble) factorize_step_matrix(*solver_, poisson_, "pressure step");
  step_factorized_ = true;
  t0 = SteadyClock::now();
  solver_->solve(rhs, wk.dp);
  f_.times.solve += seconds_since(t0);
}

void FractionalStep::correct(Work& wk) {
  const Index np = f_.cloud.n();
  const Index ne = f_.mesh.num_elements();
  const double dt = f_.step.dt;
  const Vec& v = f_.cloud.v();
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  Vec& pres = f_.cloud.p();
  // 3. Correction, and the forces of the prescribed particles.
  const auto t0 = SteadyClock::now();
  v_new_ = wk.ustar;
  wk.du = Vec::Zero(2 * np);
  element_loop(ne, scatter_, {values_of(wk.du)}, [&](Index e, std::span<double* const> out) {
    if (!rows_.mine(tri[e])) return;
    const auto& t = tri[e];
    const double dpbar = (wk.dp[t[0]] + wk.dp[t[1]] + wk.dp[t[2]]) / 3.0;
    for (int a = 0; a < 3; ++a) {
      out[0][2 * t[a]] += wk.area[e] * dpbar * wk.grad[e][a].x();
      out[0][2 * t[a] + 1] += wk.area[e] * dpbar * wk.grad[e][a].y();
    }
  });
  rows_.combine(wk.du, 2);
  for (Index k = 0; k < 2 * np; ++k)
    if (!wk.vfixed[k]) v_new_[k] += dt * wk.du[k] / wk.mass[k / 2];
  pres += wk.dp;
  // The step's inertia in the reactions of the prescribed particles (fractional_step_reactions.hpp):
  // m_a (u^{n+1} - u^n)_a / dt, or with the consistent mass (M (u* - u^n) + m (u^{n+1} - u*))_a / dt, the
  // predictor's mass and the correction's.
  const Vec inertia = s_.consistent_mass
                          ? Vec((mass_times(wk, wk.ustar - v, true) + mass_times(wk, v_new_ - wk.ustar, false)) / dt)
                          : Vec(mass_times(wk, v_new_ - v, false) / dt);
  write_prescribed_reactions(f_, {wk.area, wk.grad, wk.ustar, wk.force, wk.du, inertia, wk.implicit});
  f_.times.assembly += seconds_since(t0);
}

IterationReport FractionalStep::move_and_check(Work& wk) {
  const Index np = f_.cloud.n();
  const Index ne = f_.mesh.num_elements();
  const double dt = f_.step.dt;
  const Vec& x = f_.cloud.x();
  const std::vector<std::array<Index, 3>>& tri = f_.mesh.tri;
  const std::vector<ParticleKind>& kind = f_.cloud.kind();
  Vec& pres = f_.cloud.p();
  Vec& x_new = f_.step.x;  // the step's new positions
  auto t0 = SteadyClock::now();
  for (Index i = 0; i < np; ++i)
    if (kind[i] == ParticleKind::Fluid) {  // symplectic Euler's drift: x^{n+1} = x^n + dt u^{n+1}
      x_new.segment<2>(2 * i) = x.segment<2>(2 * i);
      SymplecticEuler::drift(x_new.segment<2>(2 * i), v_new_.segment<2>(2 * i), dt);
    }
  for (const auto& k : f_.boundaries.constraints()) x_new[2 * k.i + k.c] = f_.boundaries.position(k, f_.step.t_new);
  if (!x_new.allFinite() || !pres.allFinite() || !v_new_.allFinite())
    throw SolverError("body '" + f_.c.name +
                      "': non-finite solution of the fractional step at t = " + std::to_string(f_.step.t_new));
  // A particle of an element that moves more than 5 spacings in one step: the projection was not resolved (a
  // pocket of fluid whose pressure only the slight compressibility determines, when nothing prescribes it, took
  // a pressure of 1e8 Pa and threw a particle 70 m in one step of a dam break before the free surface at a
  // corner was marked; FluidWalls::along). The step fails and is retried with a smaller one; a
  // resolved flow moves a fraction of a spacing.
  for (Index i = 0; i < np; ++i)
    if (kind[i] == ParticleKind::Fluid && wk.mass[i] > 0 &&
        (x_new.segment<2>(2 * i) - x.segment<2>(2 * i)).norm() > 5.0 * f_.cloud.h(i))
      throw SolverError("body '" + f_.c.name + "': particle " + std::to_string(i) + " moved " +
                        std::to_string((x_new.segment<2>(2 * i) - x.segment<2>(2 * i)).norm() / f_.cloud.h(i)) +
                        " spacings in the step at t = " + std::to_string(f_.step.t_new));

  // An element turned inside out within the step: a particle crossed the opposite side of its element (a
  // neighbour at an impact, a wall). "retry" (the default) rejects the step, which the driver retries with half the
  // time step; "remesh" keeps it and the next remesh rebuilds the elements (keep_inside_walls puts back a particle
  // that went through a wall); docs/fluid_settings.md says which cases pay. An element in which a structure's
  // boundary slides past another prescribed particle (a gate's tip over the floor) is never a failure: no time step
  // resolves that, and remeshing removes it.
  inverted_in_step_ = 0;
  for (Index e = 0; e < ne; ++e)
    if (!(f_.mesh.element_area(x_new, e) > 0) && !f_.ghosts.moving_boundary_pair(tri[e], kind)) {
      ++inverted_in_step_;
      if (!s_.retry_inverted) continue;
      if (std::getenv("LAGFSI_DEBUG_NEWTON"))
        for (Index i : tri[e])
          std::fprintf(stderr,
                       "  particle %d kind %d free %d x_n (%.5f %.5f) x_new (%.5f %.5f) u (%.3f %.3f) u* (%.3f %.3f)\n",
                       int(i), int(kind[i]), int(f_.mesh.free[i]), x[2 * i], x[2 * i + 1], x_new[2 * i],
                       x_new[2 * i + 1], v_new_[2 * i], v_new_[2 * i + 1], wk.ustar[2 * i], wk.ustar[2 * i + 1]);
      throw SolverError("body '" + f_.c.name + "': element " + std::to_string(e) +
                        " turned inside out within the step at t = " + std::to_string(f_.step.t_new));
    }
  // Report: the divergence left by the correction, relative to that of the predictor (the part the
  // Laplacian stabilization does not remove).
  ThreadSums<2> divergence;  // div_star, div_new
#pragma omp parallel if (ne >= kParallelElements)
  {
    double div_star = 0, div_new = 0;
#pragma omp for schedule(static) nowait
    for (Index e = 0; e < ne; ++e) {
      const auto& t = tri[e];
      double d0 = 0, d1 = 0;
      for (int k = 0; k < 3; ++k) {
        d0 += wk.ustar.segment<2>(2 * t[k]).dot(wk.grad[e][k]);
        d1 += v_new_.segment<2>(2 * t[k]).dot(wk.grad[e][k]);
      }
      div_star += wk.area[e] * d0 * d0;
      div_new += wk.area[e] * d1 * d1;
    }
    divergence.mine() = {div_star, div_new};
  }
  const double div_star = divergence.total(0), div_new = divergence.total(1);
  f_.times.assembly += seconds_since(t0);
  IterationReport rep;
  rep.residual = std::sqrt(div_new);
  rep.residual_ref = std::max({std::sqrt(div_star), std::sqrt(div_new), 1e-300});
  rep.increment = 0;
  rep.increment_ref = f_.c.h;
  rep.converged = true;
  return rep;
}

}  // namespace

std::unique_ptr<FluidScheme> make_fractional_step(const FluidParts& f, const FractionalStepSettings& s) {
  return std::make_unique<FractionalStep>(f, s);
}

}  // namespace lagfsi::fluid
