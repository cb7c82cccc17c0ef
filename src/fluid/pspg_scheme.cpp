// PFEM fluid, scheme "monolithic_pspg": the unknowns of a step are the new positions and pressures, solved by
// Newton on the stabilized (PSPG) position-pressure system of Avancini (2018) ch. 6, in the self-consistent
// form of the digest (p positive in compression):
//
//   R^m_a = sum_e [ M_ab a_b + K_ab v_b - G_ab p_b - f_a ]                    (momentum, 2 per particle)
//   R^c_a = sum_e [ (A/3) div v + tau A grad N_a . (a_avg - g) + (tau/rho) A grad N_a . grad p
//                   + (A/3) c_vol ]                                        (continuity, 1 per particle)
//
// with P1 shape functions on the current (last iterate) configuration, Newmark (or generalized-alpha)
// kinematics a(x), v(x) from the shared time integrators, and the tangent at frozen geometry
// (d/dx of grad N and A neglected; Ryzhakov et al. 2010). c_vol is the optional global volume-correction
// source ("volume_correction": "source", volume_correction.hpp); the alpha shape's default correction ("surface")
// is geometric, see VolumeCorrection::restore_area; the advected domain's default, "particle", a local source per
// particle (volume_correction.hpp).
#include "fluid_scheme.hpp"

#include <lagfsi/assembly.hpp>
#include <lagfsi/linear_solver_input.hpp>
#include <lagfsi/mpi_run.hpp>
#include <lagfsi/parallel_sum.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace lagfsi::fluid {

PspgElementInput FluidScheme::element_input(Index e, const Vec& x, const Vec& v, const Vec& a, double c_m,
                                            double c_c) const {
  PspgElementInput in;
  const auto& t = f_.mesh.tri[e];
  const Vec& p = f_.cloud.p();
  const Vec& p_old = f_.step.p_old;
  for (int k = 0; k < 3; ++k) {
    in.x[k] = x.segment<2>(2 * t[k]);
    in.v[k] = v.segment<2>(2 * t[k]);
    in.a[k] = a.segment<2>(2 * t[k]);
    in.p[k] = p[t[k]];
    in.p_old[k] = p_old.size() == p.size() ? p_old[t[k]] : p[t[k]];
  }
  in.rho = f_.c.rho;
  in.mu = f_.boundaries.inviscid(t) ? 0.0 : f_.c.mu;
  in.dt = f_.step.dt;
  in.tau_U = tau_U_;
  in.bulk = f_.c.bulk;
  in.c_vol = f_.volume.c_vol();
  in.g = f_.c.gravity;
  in.lumped = lumped_;
  in.c_m = c_m;
  in.c_c = c_c;
  if (!robin_edges_.empty()) {
    in.robin_edges = robin_edges_[e];
    in.robin_factor = robin_factor_;
  }
  return in;
}

namespace {

class PspgScheme final : public FluidScheme {
 public:
  PspgScheme(const FluidParts& f, const PspgSettings& s, std::unique_ptr<TimeIntegrator> integrator)
      : FluidScheme(f), s_(s), integrator_(std::move(integrator)), solver_(make_linear_solver(s.solver)) {
    tau_U_ = s.tau_U;
    lumped_ = s.lumped;
    robin_factor_ = s.robin_factor;
  }
  FreeSurfacePressure free_surface_pressure() const override { return s_.free_surface; }
  Json linear_solvers() const override { return {{"newton", solver_summary(*solver_)}}; }
  bool wall_frames() const override { return true; }
  void begin_step() override {
    if (s_.free_surface == FreeSurfacePressure::robin) robin_edges_ = f_.mesh.free_surface_edges(f_.cloud.kind());
    // Over several processes with a distributed solver each computes the elements with a particle in its rows
    // (mpi_run.hpp), on the pattern of those elements alone; the particles' rows are whole blocks of 3.
    rows_.set(s_.solver.distributed, f_.cloud.n());
    // The last mesh's solver (its copy of the matrix, its preconditioner) goes before the new pattern is built.
    solver_->release();
    rows_.renew_pattern(pattern_, J_, f_.mesh.tri, f_.mesh.conn, f_.cloud.n(), 3);
    integrator_->begin_step(f_.cloud.state(), f_.step.dt);
    // A new mesh: a new Jacobian, factorized at the first iteration; re-solves of the step (restart) keep
    // the factorization of the first pass.
    iter_in_step_ = 0;
  }
  void restart() override { last_dx_ = last_dp_ = prev_dx_ = std::numeric_limits<double>::infinity(); }
  /// One Newton iteration.
  IterationReport iterate() override;
  void end_step() override {
    integrator_->end_step(f_.step.x, f_.cloud.state());
    f_.boundaries.set_motion(f_.step.t_new, f_.cloud.v(), f_.cloud.a());
    f_.ghosts.set_rates(f_.cloud.v(), f_.cloud.a());
  }
  /// The mean of v_n and the integrator's own v_{n+1} at the step's x_{n+1} (end_step on a scratch state):
  /// (x_{n+1} - x_n) / dt for the trapezoidal rule, and generalized-alpha's own velocity update under
  /// generalized-alpha (not the trapezoidal formula 2 (x_{n+1} - x_n) / dt - v_n, which is not its v_{n+1}).
  Vec step_velocity() const override {
    KinematicState end;
    integrator_->end_step(f_.step.x, end);
    return Vec(0.5 * (f_.cloud.v() + end.v));
  }

 private:
  /// The stages of an iteration: the element loop (residual R and Jacobian J_ at the evaluation point ev, the
  /// force scales, which particles have mass), the rows of particles in no element and of the walls' friction,
  /// the Dirichlet rows with the reactions they give (ghost, wall and constraint forces; returns the squared
  /// momentum residual), and the Newton correction (factorize, solve, update).
  /// `tangent`: J_ too (else R alone, and J_ keeps whatever it held).
  void assemble_elements(const EvalPoint& ev, const TangentCoefficients& cf, bool tangent, Vec& R, double& inertia2,
                         double& gravity2, double& viscous2, std::vector<char>& has_mass);
  void add_free_and_friction_rows(const EvalPoint& ev, const TangentCoefficients& cf, bool tangent, Vec& R,
                                  const std::vector<char>& has_mass);
  double apply_dirichlet(Vec& R, double sp, bool tangent);
  /// Whether this iteration sets up the solver with a new tangent: the step's first iteration (or every
  /// refactor_every-th), the others solving with it (a frozen-tangent Newton method).
  bool tangent_due() const {
    return s_.refactor_every == 0 ? iter_in_step_ == 0 : iter_in_step_ % s_.refactor_every == 0;
  }
  void correct(const Vec& R, double sp, const IterationReport& rep);
  PspgSettings s_;
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;
  /// fn(row, col, value) on each stored entry of J_. With the assembly split over processes these include rows of
  /// other processes (this process's elements add to them too); the distributed solver reads only its own rows, so
  /// what is done to the others does not matter, and no search for the own rows is needed.
  template <class Fn>
  void for_each_entry(const Fn& fn) {
    const int* outer = J_.outerIndexPtr();
    const int* inner = J_.innerIndexPtr();
    double* values = J_.valuePtr();
    for (Index col = 0; col < J_.outerSize(); ++col)
      for (int k = outer[col]; k < outer[col + 1]; ++k) fn(inner[k], col, values[k]);
  }
  /// The message of an element that turned over within the step.
  std::string inverted_message(Index e, const Vec& x) const;
  ElementPattern pattern_;
  SparseMatrix J_;
  ProcessRows rows_;       // the particles whose rows this process fills (the element assembly divided among processes)
  ThreadScatter scatter_;  // the element loop's per-thread sums
  int iter_in_step_ = 0;   // iterations of the step (all coupling passes)
  double last_dx_ = 0, last_dp_ = 0, prev_dx_ = 0;

  /// The pressure scale of the Newton test: the step's. Water at rest without gravity and without an initial
  /// pressure (a channel started from rest by a ramped inflow) has none before its first step: the iterate's own
  /// pressure, the one that accelerates the water (rho L dU/dt), is the scale then.
  double pressure_scale() const {
    return f_.step.p_scale > kNoPressureScale ? f_.step.p_scale : f_.cloud.p().cwiseAbs().maxCoeff();
  }
};

IterationReport PspgScheme::iterate() {
  auto t0 = SteadyClock::now();
  FluidStep& step = f_.step;
  Vec& x_new = step.x;
  const double h = f_.c.h;
  const Index np = f_.cloud.n();
  // Ghost particles: their velocity and acceleration are the structure's at t_{n+1}. They are written into the
  // end state and taken to the evaluation point with every other dof (under generalized-alpha, a ghost's
  // a_{n+1} among the others' a_{n+1-am} made the coupled flexible_tank unstable: its plate turned over at
  // 0.19 s). Moving walls: their motion is known at any time, so their particles take it at the evaluation
  // time itself (from the trapezoidal rule they would alternate around it after the jump of the wall's
  // velocity at the start, and the pressure in the tank then grows step after step).
  KinematicState end;
  integrator_->end_step(x_new, end);
  f_.ghosts.set_rates(end.v, end.a);
  EvalPoint ev = integrator_->evaluation(end);
  f_.boundaries.set_motion(ev.t, ev.v, ev.a);
  const TangentCoefficients cf = integrator_->coefficients();
  Vec R = Vec::Zero(3 * np);
  // The tangent only where the solver takes it (the other iterations keep the step's first: J_ is not read).
  const bool tangent = tangent_due();
  // Every stored entry (for_each_entry: the other processes' rows do not matter).
  if (tangent) std::fill(J_.valuePtr(), J_.valuePtr() + J_.nonZeros(), 0.0);
  std::vector<char> has_mass(np, 0);
  double inertia2 = 0, gravity2 = 0, viscous2 = 0;
  assemble_elements(ev, cf, tangent, R, inertia2, gravity2, viscous2, has_mass);

  add_free_and_friction_rows(ev, cf, tangent, R, has_mass);
  // Pressure columns scaled by s_p (apply_dirichlet).
  const double sp = 3.0 * f_.c.rho * h * cf.c_m;
  const double rm2 = apply_dirichlet(R, sp, tangent);
  IterationReport rep;
  rep.residual = std::sqrt(rm2);
  rep.residual_ref = std::max({std::sqrt(inertia2), std::sqrt(gravity2), std::sqrt(viscous2)});
  rep.increment = last_dx_;
  rep.increment_ref = h;
  if (!std::isfinite(rep.residual)) throw SolverError("body '" + f_.c.name + "': non-finite residual");
  f_.times.assembly += seconds_since(t0);
  // Converged: the last corrections of positions and pressures are below tolerance; or the momentum
  // residual is at round-off (1e-10 of the force scale) and the corrections stopped decreasing (the
  // frozen-geometry tangent converges linearly, and in the scaled pressure unknowns round-off keeps the
  // pressure corrections of a few particles from ever reaching tol * p_scale).
  const bool stalled = last_dx_ > 0.5 * prev_dx_ && rep.residual <= 1e-10 * rep.residual_ref && last_dx_ <= 1e-3 * h;
  if ((last_dx_ <= s_.tol * h && last_dp_ <= s_.tol * pressure_scale()) || stalled) {
    rep.converged = true;
    return rep;
  }

  correct(R, sp, rep);
  return rep;
}

void PspgScheme::assemble_elements(const EvalPoint& ev, const TangentCoefficients& cf, bool tangent, Vec& R,
                                   double& inertia2_out, double& gravity2_out, double& viscous2_out,
                                   std::vector<char>& has_mass) {
  const FluidMesh& mesh = f_.mesh;
  const std::vector<ParticleKind>& kind = f_.cloud.kind();

  const Index ne = mesh.num_elements();
  // One parallel loop over all elements (no colour barriers: on a loaded 2-core machine each OpenMP barrier of
  // busy-waiting threads can cost a time slice), each thread adding into its own copy of R and of the matrix's
  // values, merged in thread order (parallel_sum.hpp: the same sums in every run with the same threads).
  scatter_.targets({values_of(R), tangent ? values_of(J_) : std::span<double>()});
  ThreadSums<3> scales;  // inertia2, gravity2, viscous2
  std::vector<char> assembled(ne, 0);
  Index failed = ne;  // the lowest element that failed (the one reported, whatever the threads' timing)
#pragma omp parallel if (ne >= 2000)
  {
    const auto out = scatter_.arrays();
    double* const Rt = out[0];
    double* const jt = out[1];
    double inertia2 = 0, gravity2 = 0, viscous2 = 0;
#pragma omp for schedule(static) nowait
    for (Index e = 0; e < ne; ++e) {
      const auto& t = mesh.tri[e];
      // Split over processes: an element none of whose particles has its rows here is another process's (each
      // row's sum keeps the serial order of its elements); the force scales count each element once, at the
      // process of its first particle.
      if (!rows_.mine(t)) continue;
      const PspgElementInput in = element_input(e, ev.x, ev.v, ev.a, cf.c_m, cf.c_c);
      Eigen::Matrix<double, 9, 1> r;
      Eigen::Matrix<double, 9, 9> K;
      double i2 = 0, g2 = 0, v2 = 0;
      if (!(tangent ? pspg_element(in, r, K, i2, g2, &v2) : pspg_residual(in, r, i2, g2, &v2))) {
        // Turned over by a structure's boundary sliding past another prescribed particle (see
        // Ghosts::moving_boundary_pair): left out of this step, removed by the next remesh.
        if (f_.ghosts.moving_boundary_pair(t, kind)) continue;
#pragma omp critical(lagfsi_fluid_failure)
        failed = std::min(failed, e);
        continue;
      }
      if (rows_.own(t[0])) {
        inertia2 += i2;
        gravity2 += g2;
        viscous2 += v2;
      }
      // Particles on inclined walls: their momentum rows and position columns in the wall's frame (n, t).
      if (const ParticleFrames& frames = f_.boundaries.frames(); !frames.empty())
        for (int a = 0; a < 3; ++a)
          if (frames.rotated(t[a])) {
            const Mat2 Q = frames.frame(t[a]);
            r.segment<2>(3 * a) = (Q.transpose() * r.segment<2>(3 * a)).eval();
            if (!tangent) continue;
            K.block<2, 9>(3 * a, 0) = (Q.transpose() * K.block<2, 9>(3 * a, 0)).eval();
            K.block<9, 2>(0, 3 * a) = (K.block<9, 2>(0, 3 * a) * Q).eval();
          }
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) Rt[3 * t[a] + c] += r[3 * a + c];
      assembled[e] = 1;
      if (tangent) pattern_.add(e, K, jt);
    }
    scales.mine() = {inertia2, gravity2, viscous2};
  }
  scatter_.merge();
  double sums[3] = {scales.total(0), scales.total(1), scales.total(2)};
  if (rows_.split()) {
    // Each process's rows of R made whole on every process (the matrix's rows stay each process's: the
    // distributed solver reads its own), the scales summed, the failure seen by any.
    rows_.combine(R, 3);
    mpi_run::sum_in_rank_order(sums, 3);
    failed = mpi_run::min(failed);
  }
  inertia2_out = sums[0];
  gravity2_out = sums[1];
  viscous2_out = sums[2];
  for (Index e = 0; e < ne; ++e) {
    const auto& t = mesh.tri[e];
    // An element another process assembled: its particles have mass when its area is positive (pspg_element's
    // test) and it is not a structure's turned-over pair.
    const bool elsewhere = !rows_.mine(t) && mesh.element_area(ev.x, e) > 0.0;
    if (assembled[e] || elsewhere)
      for (Index i : t) has_mass[i] = 1;
  }
  if (failed < ne) throw SolverError("body '" + f_.c.name + "': " + inverted_message(failed, ev.x));
}

std::string PspgScheme::inverted_message(Index e, const Vec& x) const {
  const auto& t = f_.mesh.tri[e];
  return "element " + std::to_string(e) + " (particles " + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
         std::to_string(t[2]) + ") inverted during the step at t = " + std::to_string(f_.step.t_new) + " (area " +
         std::to_string(f_.mesh.element_area(x, e)) + ")";
}

void PspgScheme::add_free_and_friction_rows(const EvalPoint& ev, const TangentCoefficients& cf, bool tangent, Vec& R,
                                            const std::vector<char>& has_mass) {
  const std::vector<ParticleKind>& kind = f_.cloud.kind();
  const std::vector<char>& fixed = f_.step.fixed;
  const Index np = f_.cloud.n();
  const Vec2 g = f_.c.gravity;
  double* jv = J_.valuePtr();
  // "volume_correction": "particle": each particle's share of the area grows at the rate owed to it.
  if (f_.volume.type() == VolumeCorrection::Type::particle)
    for (Index i = 0; i < np; ++i)
      if (has_mass[i]) R[3 * i + 2] -= f_.volume.owed_rate(i);
  // Particles in no element fly ballistically: m (a - g) = 0 with a nominal mass, rho h_i^2.
  const int* op = J_.outerIndexPtr();
  const int* ip = J_.innerIndexPtr();
  auto diag = [&](Index dof) -> double& {
    const int* pos = std::lower_bound(ip + op[dof], ip + op[dof + 1], dof);
    return jv[pos - ip];
  };
  for (Index i = 0; i < np; ++i) {
    if (has_mass[i] || kind[i] != ParticleKind::Fluid) continue;
    const Vec2 acc = ev.a.segment<2>(2 * i) - g;
    const double m0 = f_.c.rho * f_.cloud.h(i) * f_.cloud.h(i);
    for (int c = 0; c < 2; ++c) {
      R[3 * i + c] = m0 * f_.boundaries.frames().along(acc, i, c);  // (in its frame on an inclined wall)
      if (tangent) diag(3 * i + c) += cf.c_m * m0;
    }
  }
  // No-slip walls with "navier" friction (fluid_walls.hpp): the tangential force k (v_t - v_wall,t) on each
  // fluid particle on one (d v / d x = c_c).
  for (const BoundaryFriction& w : f_.boundaries.frictions()) {
    const Index dof = 3 * w.i + w.c;
    if (!has_mass[w.i] || fixed[dof]) continue;
    const double kf = f_.boundaries.friction_coefficient(w);
    R[dof] += kf * (f_.boundaries.frames().component(ev.v, w.i, w.c) - f_.boundaries.friction_velocity(w, ev.t));
    if (tangent) diag(dof) += kf * cf.c_c;
  }
}

double PspgScheme::apply_dirichlet(Vec& R, double sp, bool tangent) {
  FluidStep& step = f_.step;
  const std::vector<char>& fixed = step.fixed;
  const Index np = f_.cloud.n();
  // Dirichlet: rows and columns of prescribed dofs become identity. Pressure columns are scaled by
  // s_p = 3 rho h c_m (p = s_p p^), which brings the pressure blocks to the size of the momentum block:
  // unscaled, the PSPG diagonal (tau/rho ~ 1e-7) is far below the pivoting threshold of the sparse LU,
  // whose off-diagonal pivots then destroy the fill-reducing ordering (4-5x slower factorizations).
  if (tangent)
    for_each_entry([&](Index row, Index col, double& value) {
      if (fixed[row] || fixed[col])
        value = row == col ? 1.0 : 0.0;
      else if (col % 3 == 2)
        value *= sp;
    });
  // Forces on the ghost particles: the reactions of their prescribed momentum rows, sign flipped (the
  // residual there is the force the structure applies to the fluid).
  Vec& ghost_force = f_.ghosts.forces();
  for (size_t gi = 0; gi < f_.ghosts.count(); ++gi)
    for (int c = 0; c < 2; ++c) ghost_force[2 * gi + c] = f_.ghosts.merged(gi) ? 0.0 : -R[3 * f_.ghosts.index(gi) + c];
  // The force each wall or ghost particle applies to the fluid (its prescribed momentum row's residual):
  // the boundary work of the energy balance; that of each wall constraint also tells whether the wall
  // pushes or pulls (WallContacts::release_pulled).
  if (step.energy) {
    Vec& boundary_force = step.boundary_force;
    boundary_force.resize(2 * f_.cloud.n_boundary_particles());
    for (Index i = 0; i < boundary_force.size() / 2; ++i)
      for (int c = 0; c < 2; ++c) boundary_force[2 * i + c] = R[3 * i + c];
  }
  {
    const auto& ks = f_.boundaries.constraints();
    step.constraint_force.resize(static_cast<Index>(ks.size()));
    for (size_t k = 0; k < ks.size(); ++k) step.constraint_force[static_cast<Index>(k)] = R[3 * ks[k].i + ks[k].c];
  }
  double rm2 = 0;
  for (Index i = 0; i < 3 * np; ++i) {
    if (fixed[i])
      R[i] = 0.0;
    else if (i % 3 != 2)
      rm2 += R[i] * R[i];
  }
  return rm2;
}

void PspgScheme::correct(const Vec& R, double sp, const IterationReport& rep) {
  const FluidStep& step = f_.step;
  Vec& x_new = f_.step.x;
  Vec& p = f_.cloud.p();
  const std::vector<char>& fixed = step.fixed;
  const double h = f_.c.h;
  const Index np = f_.cloud.n();
  auto t0 = SteadyClock::now();
  if (tangent_due()) {
    try {
      solver_->setup(J_);
    } catch (const SolverError& e) {
      throw SolverError("body '" + f_.c.name + "': " + e.what());
    }
    // Set up once a step: the solver holds what it needs of J_, which no other iteration of the step reads (the next
    // step has a new pattern), so it goes before the solves allocate their Krylov vectors.
    if (s_.refactor_every == 0) SparseMatrix().swap(J_);
  }
  ++iter_in_step_;
  f_.times.factorization += seconds_since(t0);
  t0 = SteadyClock::now();
  Vec d;
  solver_->solve(-R, d);
  f_.times.solve += seconds_since(t0);
  if (const ParticleFrames& frames = f_.boundaries.frames(); !frames.empty())  // back from the inclined walls' frames
    for (Index i = 0; i < np; ++i)
      if (frames.rotated(i)) d.segment<2>(3 * i) = (frames.frame(i) * d.segment<2>(3 * i)).eval();
  prev_dx_ = last_dx_;
  last_dx_ = last_dp_ = 0;
  for (Index i = 0; i < np; ++i) {
    x_new[2 * i] += d[3 * i];
    x_new[2 * i + 1] += d[3 * i + 1];
    const double dp = fixed[3 * i + 2] ? 0.0 : sp * d[3 * i + 2];
    p[i] += dp;
    last_dx_ = std::max({last_dx_, std::abs(d[3 * i]), std::abs(d[3 * i + 1])});
    last_dp_ = std::max(last_dp_, std::abs(dp));
  }
  if (!x_new.allFinite() || !p.allFinite()) throw SolverError("body '" + f_.c.name + "': non-finite solution");
  if (std::getenv("LAGFSI_DEBUG_NEWTON")) {  // developer aid: one line per Newton iteration on stderr
    Index worst = 0;
    for (Index i = 0; i < np; ++i)
      if (std::abs(d[3 * i]) + std::abs(d[3 * i + 1]) > std::abs(d[3 * worst]) + std::abs(d[3 * worst + 1])) worst = i;
    std::fprintf(stderr, "  t=%.6g res=%.3e ref=%.3e dx=%.3e (h %.3e) dp=%.3e (p %.3e) worst %d kind %d free %d\n",
                 step.t_new, rep.residual, rep.residual_ref, last_dx_, h, last_dp_, pressure_scale(), worst,
                 int(f_.cloud.kind()[worst]), int(f_.mesh.free[worst]));
  }
}

}  // namespace

std::unique_ptr<FluidScheme> make_pspg_scheme(const FluidParts& f, const PspgSettings& s,
                                              std::unique_ptr<TimeIntegrator> integrator) {
  return std::make_unique<PspgScheme>(f, s, std::move(integrator));
}

}  // namespace lagfsi::fluid
