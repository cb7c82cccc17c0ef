#pragma once
/// @file material_law.hpp
/// The root of every constitutive law in lagfsi, in the spirit of CB-Geo's Material: a law has a type name, the
/// isotropic elastic constants it starts from (Young's modulus E, Poisson's ratio nu, and the density rho where the
/// model is dynamic) and declares the state variables a material point of it carries (their names, in the order of
/// the point's history; none for an elastic law), which the models write to their output as fields of those names.
/// How a law is evaluated depends on the formulation, and each family adds its own contract:
///  - SolidMaterial (material.hpp): hyperelastic, total Lagrangian (F -> psi, S, dS/dE), the positional solids;
///  - mpm::MpmMaterial (lagfsi/mpm/mpm_material.hpp): a rate-form stress update (Jaumann) with a return mapping;
///  - efg::Material (lagfsi/efg/material.hpp): strain -> stress with a committed history (damage, smeared cracks).
/// The derived constants: the Lame parameters lambda = E nu / ((1 + nu)(1 - 2 nu)) and mu = E / (2 (1 + nu)) (3-D
/// and plane strain; plane stress reduces lambda where a law needs it).
#include <string>
#include <vector>

namespace lagfsi {

class MaterialLaw {
 public:
  MaterialLaw(double young, double poisson, double density) : E_(young), nu_(poisson), rho_(density) {}
  virtual ~MaterialLaw() = default;
  /// The law's name in the case file ("svk", "mohr_coulomb", "mazars", ...).
  virtual std::string type() const = 0;
  /// The names of the state variables of a material point, in the order of its history (empty: none).
  virtual std::vector<std::string> state_variables() const { return {}; }

  double young() const { return E_; }
  double poisson() const { return nu_; }
  /// Mass density (kg/m^3); 0 for a law of a static model.
  double density() const { return rho_; }
  double lame_lambda() const { return E_ * nu_ / ((1 + nu_) * (1 - 2 * nu_)); }
  double shear_modulus() const { return E_ / (2 * (1 + nu_)); }

 protected:
  double E_, nu_, rho_;
};

}  // namespace lagfsi
