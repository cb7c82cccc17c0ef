#pragma once
/// @file pressure_level.hpp (private to src/fluid)
/// The pressure level of water that no boundary sets. The pressure of an incompressible flow enters its equations
/// only through its gradient, except where a boundary gives it a value: a free surface (p = 0 imposed, or pulled
/// towards 0 by the Robin term, or traction-free in the weak form, where a constant pressure would move the
/// surface) or an outflow (p = 0). A connected part of the mesh bounded only by walls (or by a structure's ghost
/// particles) has neither: with the incompressible continuity ("bulk_modulus": 0) its pressure is defined up to a
/// constant, and its system is singular (the monolithic scheme's direct solver returns an arbitrary level, the
/// fractional step's Cholesky factorization of the pure-Neumann Poisson matrix fails). The weakly compressible
/// continuity (bulk_modulus K > 0, the default) sets the level itself, through the term (A/3)(p - p_old)/(K dt)
/// of every continuity row: the mean pressure changes only as the water's area does.
///
/// For each such part, with K = 0:
///  - without an inflow, the level is fixed by prescribing p = 0 at its highest fluid particle (against gravity;
///    the one of largest y without gravity): the pressure of still water in a closed box is then hydrostatic, zero
///    at its top, as in a tank whose lid just touches the water. A pinned value is the usual cure of a pure-Neumann
///    pressure problem (e.g. Gresho & Sani 2000, "Incompressible Flow and the Finite Element Method", vol. 2,
///    sec. 3.13); it changes no pressure gradient, so the flow is the same whatever the level (the force on one wall
///    is not: it includes the level times the wall's length).
///  - with an inflow into it, the water the inflow brings has nowhere to go (an incompressible
///    part's area is fixed by its walls): the run stops with one line naming the inflow and the cures (an outflow, a
///    free surface, a bulk_modulus).
/// A part bounded in part by a structure's ghost particles is also pinned: the level is then the one the partitioned
/// (Dirichlet-Neumann) coupling cannot determine either (the "incompressibility dilemma", Kuettler et al. 2006),
/// and the structure is loaded by the pressure relative to its top.
#include "fluid_mesh.hpp"

#include <lagfsi/fluid/particle_cloud.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace lagfsi::fluid {

/// What anchor_pressure_level found.
struct PressureLevelParts {
  int pinned = 0;   ///< parts whose level it pinned (p = 0 at their highest particle)
  int inflow = -1;  ///< the first inflow (its index among the case's boundaries) that feeds an enclosed part, or -1
};

/// For each connected part of the mesh (particles joined by elements) with no pressure anchor: no particle outside
/// the inlets whose pressure is prescribed (`fixed`, three flags per particle, the third the pressure's) or that is
/// on the free surface (`free`, per particle): with `bulk` (the bulk modulus) 0, pins the pressure of its highest
/// fluid particle (along -gravity) in `fixed`, or, if a particle of it lies in an inflow's inlet layer (`inflow`,
/// per particle: the case boundary's index or -1), reports that inflow and pins nothing there. Does nothing with
/// bulk > 0. The inlets' particles are no anchor: those an inflow holds keep their pressure unknown, and the two
/// the walls hold at its ends are marked free surface (p = 0 with the Dirichlet condition) by the unshared edge
/// along the inlet, a p = 0 that does not give the water the inflow brings a way out.
PressureLevelParts anchor_pressure_level(const FluidMesh& mesh, const ParticleCloud& cloud,
                                         const std::vector<std::uint8_t>& free, const std::vector<int>& inflow,
                                         const Vec2& gravity, double bulk, std::vector<char>& fixed);

}  // namespace lagfsi::fluid
