#pragma once
/// @file material.hpp
/// Constitutive laws of the EFG module: one interface, one class per law (thesis Ch. 3 and §5; Penna 2011's
/// "grey box": strain in, stress, secant or tangent operator and updated internal variables out).
///
/// Strains and stresses are 2-D engineering vectors [e_xx, e_yy, gamma_xy], [s_xx, s_yy, s_xy]. A law computes
/// the stress from the strain and the *committed* history h0 and writes the trial history h1; the model commits
/// h1 only when the load step converged, so an iteration or a failed step never changes h0 (rollback = forget h1).
/// Operators: secant E_s (sigma = E_s eps) from the law, tangent E_t = d sigma / d eps at h0 by a forward
/// difference of the stress update (consistent with it, including the branch switch of a loading point).
///
/// Laws:
///  - linear_elastic (plane stress or plane strain);
///  - mazars (Mazars 1984): eps~ = sqrt(sum <eps_i>+^2) over principal strains (with eps_zz), kappa = max(kappa0,
///    max eps~), D_t,c = 1 - kappa0 (1 - A_t,c)/kappa - A_t,c exp(-B_t,c (kappa - kappa0)), D = a_t D_t + a_c D_c,
///    a_t = sum <eps_Ti> <eps_i>+ / eps~^2 from the effective-stress split; sigma = (1 - D) E0 eps;
///  - exponential_damage: Mazars eps~, D = 1 - (kappa0/kappa)[1 - alpha + alpha exp(-beta (kappa - kappa0))];
///  - smeared_crack: rotating total-strain smeared crack; in principal strain directions equivalent uniaxial strains
///    eb_i = (eps_i + nu eps_j)/(1 - nu^2) follow uniaxial laws with secant unloading: compression Carreira & Chu
///    (1985) s/f_c = b (e/e_c)/(b - 1 + (e/e_c)^b), b = 1/(1 - f_c/(e_c E0)); tension either linear to f_t then
///    exponential softening s = f_t exp[-(e - e0)/e_f], e0 = f_t/E0, e_f = G_f/(h f_t) - e0/2 (area under the
///    curve G_f/h: fracture energy over the crack band h; the digest's default for Boone et al. 1986) or Carreira & Chu
///    (1986) with f_t, e_t; shear modulus from coaxiality (s_1 - s_2)/(2 (e_1 - e_2)).
#include <lagfsi/material_law.hpp>
#include <lagfsi/params.hpp>

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>

namespace lagfsi::efg {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Internal variables of one material point (meaning and names per law: Material::state_variables).
struct History {
  std::array<double, 3> h{0.0, 0.0, 0.0};
};

enum class Operator { secant, tangent };

/// A law of the EFG module (material_law.hpp: the constants, the type and the names of its history's entries; no
/// density: the EFG analyses are static).
class Material : public MaterialLaw {
 public:
  Material(double young, double poisson, bool plane_strain);
  virtual bool linear() const { return false; }
  /// Stress and secant operator at strain eps from committed history h0; trial history into h1.
  virtual void stress(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& Es) const = 0;
  /// A scalar damage measure of a history (0 intact, 1 fully damaged) for output.
  virtual double damage(const History& h) const {
    (void)h;
    return 0.0;
  }
  /// Strain scale of the law (kappa0, f_t/E0): sets the finite-difference step of the tangent.
  virtual double strain_scale() const { return 1e-4; }
  /// Stress, trial history and the operator asked for (tangent by forward differences of stress()).
  void evaluate(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& E, Operator op) const;
  const Mat3& elastic() const { return D0_; }
  bool plane_strain() const { return plane_strain_; }
  /// Out-of-plane strain of an elastic-degraded state (plane stress: -nu/(1-nu)(e_xx + e_yy); plane strain: 0).
  double eps_zz(const Vec3& eps) const;

 protected:
  bool plane_strain_;
  Mat3 D0_;
};

/// Builds a law from {"type": ..., "young", "poisson", "hypothesis": "plane_stress"|"plane_strain", ...}.
/// Bad values fail at their JSON path.
std::unique_ptr<Material> make_material(Params p);

/// Principal strains (e1 >= e2) of an engineering strain vector and the angle of e1 to x.
void principal_strains(const Vec3& eps, double& e1, double& e2, double& theta);
/// Mazars' equivalent strain sqrt(sum <e_i>+^2) over the principal strains and e_zz.
double mazars_equivalent_strain(const Vec3& eps, double ezz);

}  // namespace lagfsi::efg
