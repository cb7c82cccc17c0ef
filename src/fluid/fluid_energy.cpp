// The fluid's energies (fluid_energy.hpp): kinetic and potential energy, work of gravity and dissipation.
#include "fluid_energy.hpp"

#include <lagfsi/mpi_run.hpp>

#include <algorithm>

namespace lagfsi::fluid {

namespace {

/// The totals of the elements [first, last) (FluidEnergy::Totals).
FluidEnergy::Totals element_totals(const FluidConstants& c, const Vec& x, const Vec& v, const FluidMesh& mesh,
                                   Index first, Index last) {
  FluidEnergy::Totals t;
  for (Index k = first; k < last; ++k) {
    const double a = mesh.element_area(x, k);
    t.area += a;
    const double m = c.rho * a / 3.0;
    Vec2 cx = Vec2::Zero();
    for (Index i : mesh.tri[k]) {
      t.kinetic += 0.5 * m * v.segment<2>(2 * i).squaredNorm();
      cx += x.segment<2>(2 * i);
    }
    t.potential -= c.rho * a * c.gravity.dot(cx / 3.0);
  }
  return t;
}

}  // namespace

FluidEnergy::Totals FluidEnergy::totals() const {
  return element_totals(c_, cloud_.x(), cloud_.v(), mesh_, 0, mesh_.num_elements());
}

FluidEnergy::Totals FluidEnergy::totals_over_processes() const {
  if (mpi_run::size() <= 1) return totals();
  const auto [first, last] = mpi_run::owned_blocks(mesh_.num_elements());
  const Totals mine = element_totals(c_, cloud_.x(), cloud_.v(), mesh_, first, last);
  double sums[] = {mine.area, mine.kinetic, mine.potential};
  mpi_run::sum_in_rank_order(sums, 3);
  return {sums[0], sums[1], sums[2]};
}

void FluidEnergy::account(const Vec& x_new, const Vec& v, double t, double dt, const Vec& boundary_force,
                          const Vec& constraint_force) {
  // On the step's mesh at x_n (lumped masses m_i = sum rho A/3, walls and ghosts included: their share of
  // the fluid moves with them): work of gravity sum m_i g . (x_{n+1} - x_n) and viscous dissipation
  // dt sum_e 2 mu A eps(v):eps(v) of the step's velocity (v_{n+1} for the fractional step, the mean of
  // v_n and v_{n+1} for the trapezoidal rule).
  const Vec& x = cloud_.x();
  const Index ne = mesh_.num_elements();
  double gw = 0, diss = 0;
  for (Index e = 0; e < ne; ++e) {
    const auto& t = mesh_.tri[e];
    const double A = mesh_.element_area(x, e);
    if (!(A > 0)) continue;
    Mat2 L = Mat2::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec2& p = x.segment<2>(2 * t[(k + 1) % 3]);
      const Vec2& q = x.segment<2>(2 * t[(k + 2) % 3]);
      const Vec2 grad = Vec2(p.y() - q.y(), q.x() - p.x()) / (2 * A);
      L += v.segment<2>(2 * t[k]) * grad.transpose();
      gw += c_.rho * A / 3.0 * c_.gravity.dot(x_new.segment<2>(2 * t[k]) - x.segment<2>(2 * t[k]));
    }
    if (c_.mu > 0 && !boundaries_.inviscid(t)) {
      const Mat2 eps = 0.5 * (L + L.transpose());
      diss += dt * 2.0 * c_.mu * A * (eps.array() * eps.array()).sum();
    }
  }
  // The friction of the no-slip walls under "navier" (fluid_walls.hpp): k |v_t - v_wall,t|^2 dt.
  const ParticleFrames& frames = boundaries_.frames();
  for (const BoundaryFriction& f : boundaries_.frictions()) {
    const double dv = frames.component(v, f.i, f.c) - boundaries_.friction_velocity(f, t);
    diss += dt * boundaries_.friction_coefficient(f) * dv * dv;
  }
  gravity_work_ += gw;
  dissipation_ += diss;
  // Work of the moving walls and ghosts on the fluid: the mean of the step's start and end forces times
  // the step's displacement (their indices are stable: walls, then ghosts, come first in the cloud).
  const Index nb = std::min<Index>(static_cast<Index>(boundary_force.size() / 2), cloud_.n_boundary_particles());
  if (boundary_force_prev_.size() != boundary_force.size()) boundary_force_prev_ = boundary_force;
  for (Index i = 0; i < nb; ++i)
    boundary_work_ += 0.5 * (boundary_force_prev_.segment<2>(2 * i) + boundary_force.segment<2>(2 * i))
                                .dot(x_new.segment<2>(2 * i) - x.segment<2>(2 * i));
  boundary_force_prev_ = boundary_force;
  // Work of the walls and boundaries through the constraints of the particles on them: the end-of-step force
  // times the step's displacement (first order: the constrained particles change from step to step).
  const auto& ks = boundaries_.constraints();
  if (static_cast<size_t>(constraint_force.size()) == ks.size())
    for (size_t k = 0; k < ks.size(); ++k) {
      const double dx =
          boundaries_.frames().component(x_new, ks[k].i, ks[k].c) - boundaries_.frames().component(x, ks[k].i, ks[k].c);
      boundary_work_ += constraint_force[static_cast<Index>(k)] * dx;
    }
}

}  // namespace lagfsi::fluid
