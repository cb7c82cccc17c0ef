#pragma once
/// @file fractional_step_reactions.hpp (private to src/fluid)
/// The forces that the prescribed particles of a fractional step (fractional_step.cpp) apply to the fluid: the
/// ghost particles' (the load on a structure), the wall and ghost particles' (the boundary work of the energy balance,
/// wall_force probes) and those of the components held by wall constraints. For a particle a whose velocity the step
/// prescribes, the fluid's momentum balance leaves the force
///
///     F_a = I_a - f_a - du_a + (K u*)_a
///
/// that the boundary applies to the fluid: I the step's inertia (lumped, m_a (u^{n+1} - u^n)_a / dt; with the
/// consistent mass, (M (u* - u^n) + m (u^{n+1} - u*))_a / dt), f the predictor's explicit forces (gravity, the last
/// step's pressure, the explicit viscous force), du the pressure increment's force, and K u* the implicit viscous
/// predictor's Laplacian at u*, K_ab = sum_e mu A_e grad N_a . grad N_b (zero with the explicit predictor).
#include "fluid_scheme.hpp"

#include <array>
#include <vector>

namespace lagfsi::fluid {

/// A fractional step's terms, per element (the step mesh's areas and shape-function gradients) and per particle
/// component (2 per particle).
struct FractionalStepTerms {
  const std::vector<double>& area;
  const std::vector<std::array<Vec2, 3>>& grad;
  const Vec& ustar;    ///< u*, the predictor's velocities
  const Vec& force;    ///< f, the predictor's explicit forces
  const Vec& du;       ///< the pressure increment's force, sum_e A_e dpbar_e grad N_a
  const Vec& inertia;  ///< I, the step's inertia
  bool implicit;       ///< the viscous predictor is implicit (K u* enters the reactions)
};

/// Writes the reactions: the ghosts' forces (the force on the structure, F with its sign flipped; zero for a merged
/// ghost), f.step.boundary_force when f.step.energy asks for it, and f.step.constraint_force for the components held
/// by wall constraints.
void write_prescribed_reactions(const FluidParts& f, const FractionalStepTerms& t);

}  // namespace lagfsi::fluid
