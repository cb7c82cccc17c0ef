// The forces of a fractional step's prescribed particles (fractional_step_reactions.hpp).
#include "fractional_step_reactions.hpp"

namespace lagfsi::fluid {

namespace {

/// K u* in the rows of the particles `wanted` selects, K_ab = sum_e mu A_e grad N_a . grad N_b over the viscous
/// elements; zero with the explicit predictor, whose viscous term is in the forces f.
template <class Wanted>
Vec viscous_rows(const FluidParts& f, const FractionalStepTerms& t, const Wanted& wanted) {
  const Index np = f.cloud.n();
  const Index ne = f.mesh.num_elements();
  Vec Ku = Vec::Zero(2 * np);
  if (!t.implicit) return Ku;
  for (Index e = 0; e < ne; ++e) {
    const auto& el = f.mesh.tri[e];
    if (f.boundaries.inviscid(el) || !(wanted(el[0]) || wanted(el[1]) || wanted(el[2]))) continue;
    for (int a = 0; a < 3; ++a)
      if (wanted(el[a]))
        for (int b = 0; b < 3; ++b)
          Ku.segment<2>(2 * el[a]) +=
              f.c.mu * t.area[e] * t.grad[e][a].dot(t.grad[e][b]) * t.ustar.segment<2>(2 * el[b]);
  }
  return Ku;
}

}  // namespace

void write_prescribed_reactions(const FluidParts& f, const FractionalStepTerms& t) {
  const Index np = f.cloud.n();
  if (f.ghosts.count() > 0) {
    // What the structure must apply to give its ghosts the prescribed velocity: -F.
    Vec& ghost_force = f.ghosts.forces();
    const Vec Ku = viscous_rows(f, t, [&](Index i) { return f.ghosts.is_ghost(i); });
    for (size_t gi = 0; gi < f.ghosts.count(); ++gi) {
      const Index i = f.ghosts.index(gi);
      if (f.ghosts.merged(gi)) {
        ghost_force.segment<2>(2 * gi).setZero();
        continue;
      }
      ghost_force.segment<2>(2 * gi) =
          t.force.segment<2>(2 * i) + t.du.segment<2>(2 * i) - Ku.segment<2>(2 * i) - t.inertia.segment<2>(2 * i);
    }
  }
  if (f.step.energy) {
    // The force each wall or ghost particle applies to the fluid (the boundary work of the energy balance).
    const Index nb = f.cloud.n_boundary_particles();
    const Vec Ku = viscous_rows(f, t, [&](Index i) { return i < nb; });
    Vec& boundary_force = f.step.boundary_force;
    boundary_force.resize(2 * nb);
    for (Index i = 0; i < nb; ++i)
      boundary_force.segment<2>(2 * i) =
          t.inertia.segment<2>(2 * i) - t.force.segment<2>(2 * i) - t.du.segment<2>(2 * i) + Ku.segment<2>(2 * i);
  }
  if (!f.boundaries.constraints().empty()) {
    // The same for the constrained components of the particles on walls (the energy balance, and whether the
    // wall pushes or pulls: WallContacts::release_pulled).
    const auto& ks = f.boundaries.constraints();
    Vec& kf = f.step.constraint_force;
    kf.resize(static_cast<Index>(ks.size()));
    const std::vector<char> on_wall = f.boundaries.on_wall(np);
    const Vec Kw = viscous_rows(f, t, [&](Index i) { return on_wall[i] != 0; });
    for (size_t k = 0; k < ks.size(); ++k) {
      const Index j = 2 * ks[k].i + ks[k].c;
      kf[static_cast<Index>(k)] = t.inertia[j] - t.force[j] - t.du[j] + Kw[j];
    }
  }
}

}  // namespace lagfsi::fluid
