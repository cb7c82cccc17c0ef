#pragma once
/// @file fluid_element.hpp
/// The P1/P1 PSPG element of the PFEM fluid in positions and pressures (Avancini 2018, ch. 6, in the
/// digest's self-consistent form, p positive in compression): for the element's three particles a,
///
///   r^m_a = M_ab a_b + A mu (grad v + grad v^T) grad N_a - A p_mean grad N_a - (rho A / 3) g
///   r^c_a = (A/3)(div v + c_vol) + tau A grad N_a . (a_mean - g) + (tau/rho) A grad N_a . grad p
///           + (A/3)(p_a - p_a,old) / (K dt)
///           + sum over the element's free-surface edges E at a: beta_E (p_a - 2 mu n.eps(v).n)
///
/// The last term is the free surface's Robin condition ("free_surface_pressure": "robin"): the continuity is
/// kept at the free-surface particles and their pressure is pulled weakly to the normal viscous stress (the
/// traction-free condition) with beta_E = f (tau/rho)(2/h_n)(L/2), h_n = 2A/L the element's height over the
/// edge of length L and outward normal n (lumped on the edge's two particles). With f = 1 it is the boundary
/// term of the FIC mass balance of Onate, Franci & Carbonell (2014, Int. J. Numer. Meth. Fluids 74: 699-731),
/// which the Kratos PFEM fluid keeps for its reduced mass losses (here without its acceleration term): the
/// pressure extrapolated to zero half an element outside the surface. f -> 0 is the natural condition (the
/// continuity exact at the surface, but a drop's or film's pressure is then set by its area alone); f -> inf
/// is p = 0 (Dirichlet: no continuity at the surface particles, where a splash loses its area).
///
/// with M lumped (rho A/3) or consistent (rho A/12 (1 + delta_ab)), A and grad N on the given geometry (the
/// current iterate: updated Lagrangian, F = I), and tau = [(2/dt)^2 + (2|v_mean|/h_e)^2 + (4 nu/h_e^2)^2]^(-1/2)
/// (automatic) or Tezduyar's h_e/(2U) z(Re_U) with a velocity scale U (Tezduyar et al. 1992), h_e = 2 sqrt(A/pi).
///
/// The tangent is d r / d(x_b, p_b) at frozen geometry: a and v depend on x through the time integrator
/// (d a/dx = c_m, d v/dx = c_c); the derivatives of A and grad N with respect to x are neglected (Ryzhakov et
/// al. 2010). Local dof order: (x, y, p) per particle.
#include <lagfsi/types.hpp>

#include <Eigen/Dense>

namespace lagfsi {

struct PspgElementInput {
  Vec2 x[3], v[3], a[3];  ///< geometry (evaluation configuration), velocities, accelerations
  double p[3], p_old[3];  ///< pressures (iterate and start of step)
  double rho = 1000, mu = 1e-3, dt = 1e-3;
  double tau_U = 0;  ///< 0: automatic tau; > 0: Tezduyar's user velocity scale
  double bulk = 0;   ///< bulk modulus of the slight compressibility (0: none)
  double c_vol = 0;  ///< global volume-correction source
  Vec2 g = Vec2::Zero();
  bool lumped = true;
  double c_m = 0, c_c = 0;   ///< d a / d x and d v / d x of the time integrator
  unsigned robin_edges = 0;  ///< bit k: the edge from particle k to k+1 is free surface (Robin term)
  double robin_factor = 0;   ///< f of the Robin term (0: none)
};

/// Residual r (9) and frozen-geometry tangent K (9 x 9) of one element; inertia2 and gravity2 get the
/// squared norms of the nodal inertia and gravity forces, and viscous2 (when given) those of the viscous forces
/// (for the residual reference: a flow driven by its boundaries alone, from rest and without gravity, has no
/// other force at its first iteration). Returns false (and leaves the outputs unspecified) when the element's
/// area is not positive.
bool pspg_element(const PspgElementInput& in, Eigen::Matrix<double, 9, 1>& r, Eigen::Matrix<double, 9, 9>& K,
                  double& inertia2, double& gravity2, double* viscous2 = nullptr);
/// The residual alone, the same bits as pspg_element's: for the Newton iterations that keep the step's first tangent
/// (a frozen-tangent Newton method, PspgSettings::refactor_every).
bool pspg_residual(const PspgElementInput& in, Eigen::Matrix<double, 9, 1>& r, double& inertia2, double& gravity2,
                   double* viscous2 = nullptr);

}  // namespace lagfsi
