#pragma once
/// @file mpm/mpm_material.hpp
/// Constitutive laws of the MPM particles (in the style of CB-Geo's Material<Tdim>: one object per body,
/// shared by its particles, that updates a particle's stress by a strain increment). Small strain rate,
/// plane strain, stress (xx, yy, xy, zz) tension positive.
///
///  - "linear_elastic": sigma += C : d + (W sigma - sigma W) (Jaumann rate), C the isotropic stiffness
///                      (lambda, mu).
///  - "mohr_coulomb":   the same elastic trial, then the return mapping onto the Mohr-Coulomb surface
///                      (principal stresses: main plane, edges, apex) with a non-associated flow of
///                      dilatancy angle psi, and an optional tension cut-off below the apex c cot(phi).
///
/// The elastic constants are also the tangent of the implicit scheme and give the wave speeds of the
/// explicit step and of the absorbing boundaries.
#include <lagfsi/material_law.hpp>
#include <lagfsi/mpm/mpm_state.hpp>
#include <lagfsi/params.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::mpm {

/// Strain increment of a step, d = dt sym(L) (tensor components xx, yy, xy), and the spin w = dt W_xy,
/// W = (L - L^T) / 2.
struct StrainIncrement {
  double xx = 0, yy = 0, xy = 0, spin = 0;
};

/// A law of the MPM particles (material_law.hpp: the constants, the type and the declared state variables).
class MpmMaterial : public MaterialLaw {
 public:
  MpmMaterial(double young, double poisson, double density);
  /// Whether the law has a yield surface (else linear elastic).
  virtual bool plastic() const = 0;

  /// Updates a particle's stress by the increment: the elastic trial, then the law's return mapping. Returns
  /// the increment of the plastic multiplier (0 if elastic).
  double update_stress(Stress& s, const StrainIncrement& d) const {
    elastic_trial(s, d);
    return plastic() ? return_mapping(s) : 0.0;
  }
  /// The elastic trial of a step: s += C : d + (W s - s W) (Jaumann rate: the stress turns with the spin
  /// W = (L - L^T)/2, w = W_xy dt).
  void elastic_trial(Stress& s, const StrainIncrement& d) const {
    const double tr = d.xx + d.yy;
    const double w = d.spin;
    const double rxx = 2 * w * s[2], rxy = w * (s[1] - s[0]);
    s[0] += lambda_ * tr + 2 * mu_ * d.xx + rxx;
    s[1] += lambda_ * tr + 2 * mu_ * d.yy - rxx;
    s[2] += 2 * mu_ * d.xy + rxy;
    s[3] += lambda_ * tr;
  }
  /// Corrects an elastic trial stress onto the admissible domain; returns the plastic multiplier (0: the trial
  /// is admissible and unchanged).
  virtual double return_mapping(Stress& s) const = 0;
  /// Adds the linear elastic increment C : d (no rotation, no return mapping) to s.
  void add_elastic_increment(Stress& s, double dxx, double dyy, double dxy) const;

  /// P-wave speed sqrt((lambda + 2 mu) / rho) and S-wave speed sqrt(mu / rho).
  double p_wave_speed() const { return std::sqrt((lambda_ + 2 * mu_) / rho_); }
  double s_wave_speed() const { return std::sqrt(mu_ / rho_); }

 protected:
  double lambda_, mu_;  // the Lame parameters (MaterialLaw's), kept for the stress update
};

class LinearElastic final : public MpmMaterial {
 public:
  using MpmMaterial::MpmMaterial;
  std::string type() const override { return "linear_elastic"; }
  bool plastic() const override { return false; }
  double return_mapping(Stress&) const override { return 0.0; }
};

/// Mohr-Coulomb with cohesion c, friction angle phi, dilatancy angle psi <= phi (degrees) and a tension
/// cut-off: no principal stress above it (at most, and by default, the apex c cot(phi)).
class MohrCoulomb final : public MpmMaterial {
 public:
  /// tension_cutoff < 0: at the apex c cot(phi).
  MohrCoulomb(double young, double poisson, double density, double cohesion, double friction_angle,
              double dilatancy_angle, double tension_cutoff = -1.0);
  std::string type() const override { return "mohr_coulomb"; }
  std::vector<std::string> state_variables() const override { return {"plastic_multiplier"}; }
  bool plastic() const override { return true; }
  double return_mapping(Stress& s) const override;

  double cohesion() const { return cohesion_; }
  double sin_phi() const { return sin_phi_; }
  double cos_phi() const { return cos_phi_; }
  double sin_psi() const { return sin_psi_; }
  double tension_cutoff() const { return tension_cutoff_; }
  /// Mean stress at the apex of the surface, c cot(phi).
  double apex() const { return sin_phi_ > 0 ? cohesion_ * cos_phi_ / sin_phi_ : 0.0; }
  /// The yield function of the principal stresses s1 >= s2 >= s3 (the main plane through s1 and s3):
  /// f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi).
  double yield_function(double s1, double s3) const {
    return (s1 - s3) + (s1 + s3) * sin_phi_ - 2 * cohesion_ * cos_phi_;
  }

 private:
  double cohesion_, sin_phi_, cos_phi_, sin_psi_, tension_cutoff_;
};

/// The material of an MPM body from its "material" object ({"type": "linear_elastic" | "mohr_coulomb", ...});
/// throws InputError for a bad one.
std::unique_ptr<MpmMaterial> make_mpm_material(Params mat);

}  // namespace lagfsi::mpm
