#pragma once
/// @file material.hpp
/// Hyperelastic laws for 2D solids in the positional formulation: given the in-plane deformation
/// gradient F (2x2), the law returns the strain energy density psi (per unit reference volume), the
/// second Piola-Kirchhoff stress S (2x2, in-plane) and the material tangent D = dS/dE in Voigt form
/// with rows/columns (11, 22, 12) acting on tensor components (so S_ij = D_ijkl E_kl becomes
/// S_v = D_v * [E11, E22, 2 E12]).
///
/// Plane strain: F33 = 1. Plane stress: S33 = 0; for SVK this is the classical reduced modulus
/// lambda* = 2 lambda mu / (lambda + 2 mu); for Neo-Hookean C33 is found by a scalar Newton solve and
/// the tangent is statically condensed.
///
///  - "svk"         Saint-Venant-Kirchhoff: psi = lambda/2 (tr E)^2 + mu E:E, S = lambda tr(E) I + 2 mu E.
///                  Valid for small strains only (it softens and loses stability in strong compression).
///  - "neo_hookean" compressible Neo-Hookean (Bonet & Wood 2008, eq. 6.28):
///                  psi = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2,
///                  S = mu (I - C^-1) + lambda ln J C^-1.
#include <lagfsi/material_law.hpp>
#include <lagfsi/types.hpp>

#include <Eigen/Dense>
#include <memory>
#include <string>

namespace lagfsi {

enum class PlaneHypothesis { PlaneStrain, PlaneStress };

struct MaterialResponse {
  double psi = 0.0;                             ///< strain energy per unit reference volume
  Mat2 S = Mat2::Zero();                        ///< second Piola-Kirchhoff stress (in-plane)
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();  ///< dS/dE (Voigt 11, 22, 12; engineering shear)
  double S33 = 0.0;                             ///< out-of-plane S (plane strain; 0 in plane stress)
  double F33 = 1.0;                             ///< out-of-plane stretch (1 in plane strain)
};

/// A hyperelastic law of the positional solids and shells (material_law.hpp: the constants and the type; no state
/// variables: the stress follows from the current deformation alone).
class SolidMaterial : public MaterialLaw {
 public:
  SolidMaterial(double E, double nu, double rho, PlaneHypothesis h) : MaterialLaw(E, nu, rho), hyp_(h) {}
  /// Evaluates the law at F. Throws SolverError if det F <= 0 (inverted element).
  virtual MaterialResponse evaluate(const Mat2& F) const = 0;
  PlaneHypothesis hypothesis() const { return hyp_; }

 protected:
  PlaneHypothesis hyp_;
};

/// Builds "svk" or "neo_hookean"; throws std::invalid_argument for an unknown type.
std::unique_ptr<SolidMaterial> make_solid_material(const std::string& type, double E, double nu, double rho,
                                                   PlaneHypothesis h);

}  // namespace lagfsi
