#include <lagfsi/error.hpp>
#include <lagfsi/material.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace lagfsi {

namespace {

// Voigt rows/columns (11, 22, 12) as tensor index pairs.
constexpr int kVoigt[3][2] = {{0, 0}, {1, 1}, {0, 1}};

std::string format_number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

/// det F of an admissible deformation gradient; throws SolverError for det F <= 0 or non-finite F.
double checked_det(const Mat2& F) {
  const double J = F.determinant();
  if (!F.allFinite() || !std::isfinite(J) || !(J > 0.0))
    throw SolverError("inverted element (det F = " + format_number(J) + ")");
  return J;
}

// ------------------------------------------------------------------ Saint-Venant-Kirchhoff

class SvkMaterial final : public SolidMaterial {
 public:
  using SolidMaterial::SolidMaterial;
  std::string type() const override { return "svk"; }

  MaterialResponse evaluate(const Mat2& F) const override {
    checked_det(F);
    const double lam = lame_lambda(), mu = shear_modulus();
    const bool stress = hypothesis() == PlaneHypothesis::PlaneStress;
    // Plane stress: E33 = -lam/(lam + 2 mu) tr E makes S33 = 0 and leaves the in-plane law with the
    // reduced modulus lam* = 2 lam mu / (lam + 2 mu).
    const double l = stress ? 2.0 * lam * mu / (lam + 2.0 * mu) : lam;

    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    const double trE = E.trace();
    MaterialResponse r;
    r.psi = 0.5 * l * trE * trE + mu * E.squaredNorm();
    r.S = l * trE * Mat2::Identity() + 2.0 * mu * E;
    r.D << l + 2.0 * mu, l, 0.0, l, l + 2.0 * mu, 0.0, 0.0, 0.0, mu;
    if (stress) {
      const double E33 = -lam / (lam + 2.0 * mu) * trE;
      const double c33 = 1.0 + 2.0 * E33;
      if (!(c33 > 0.0))
        throw SolverError("svk plane stress: no admissible thickness stretch (C33 = " + format_number(c33) + ")");
      r.S33 = 0.0;
      r.F33 = std::sqrt(c33);
    } else {
      r.S33 = lam * trE;
      r.F33 = 1.0;
    }
    return r;
  }
};

// ------------------------------------------------------------------ compressible Neo-Hookean

class NeoHookeanMaterial final : public SolidMaterial {
 public:
  using SolidMaterial::SolidMaterial;
  std::string type() const override { return "neo_hookean"; }

  MaterialResponse evaluate(const Mat2& F) const override {
    const double j2 = checked_det(F);  // in-plane det F
    const double lam = lame_lambda(), mu = shear_modulus();
    const bool stress = hypothesis() == PlaneHypothesis::PlaneStress;

    const Mat2 C = F.transpose() * F;
    const Mat2 Ci = C.inverse();
    const double c33 = stress ? solve_c33(std::log(j2), lam, mu) : 1.0;
    const double lnJ = std::log(j2) + 0.5 * std::log(c33);

    MaterialResponse r;
    r.psi = 0.5 * mu * (C.trace() + c33 - 3.0) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
    r.S = mu * (Mat2::Identity() - Ci) + lam * lnJ * Ci;

    // 3D tangent C_IJKL = lam Ci_IJ Ci_KL + 2 (mu - lam ln J) 1/2 (Ci_IK Ci_JL + Ci_IL Ci_JK),
    // restricted to the in-plane indices (Ci_I3 = 0 for in-plane I).
    const double m = mu - lam * lnJ;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int i = kVoigt[a][0], j = kVoigt[a][1], k = kVoigt[b][0], l = kVoigt[b][1];
        r.D(a, b) = lam * Ci(i, j) * Ci(k, l) + m * (Ci(i, k) * Ci(j, l) + Ci(i, l) * Ci(j, k));
      }

    if (stress) {
      // Static condensation of E33 under S33 = 0: D2 = Dpp - Dp3 D3p / D33, with
      // C_ij33 = lam Ci_ij / C33 and C_3333 = (lam + 2 m) / C33^2. At the plane-stress solution
      // lam ln J = mu (1 - C33), so lam + 2 m = lam + 2 mu C33 = 2 dh/du > 0 (the stable root).
      Eigen::Vector3d d;
      for (int a = 0; a < 3; ++a) d(a) = lam * Ci(kVoigt[a][0], kVoigt[a][1]) / c33;
      const double d33 = (lam + 2.0 * m) / (c33 * c33);
      if (!(d33 > 0.0)) throw SolverError("neo_hookean plane stress: non-positive out-of-plane stiffness");
      r.D -= d * d.transpose() / d33;
      r.S33 = 0.0;
      r.F33 = std::sqrt(c33);
    } else {
      r.S33 = lam * lnJ;  // mu (1 - 1/C33) + lam ln J / C33 with C33 = 1
      r.F33 = 1.0;
    }
    return r;
  }

 private:
  /// C33 such that S33 = mu (1 - 1/C33) + lam ln J / C33 = 0, i.e. h = mu (C33 - 1) + lam ln J = 0 with
  /// ln J = ln j2 + ln(C33)/2. Newton in u = ln C33 (positivity is automatic): h(u) is convex and,
  /// from u = 0 where h' = mu + lam/2 > 0 for every nu in (-1, 1/2), Newton converges monotonically
  /// to the stable root after the first step.
  static double solve_c33(double ln_j2, double lam, double mu) {
    double u = 0.0;
    for (int it = 0; it < 50; ++it) {
      const double eu = std::exp(u);
      const double h = mu * (eu - 1.0) + lam * (ln_j2 + 0.5 * u);
      const double dh = mu * eu + 0.5 * lam;
      if (!std::isfinite(h) || !(dh > 0.0)) break;
      const double du = h / dh;
      u -= du;
      if (std::abs(du) <= 1e-14 * std::max(1.0, std::abs(u))) return std::exp(u);
    }
    throw SolverError(
        "neo_hookean plane stress: the S33 = 0 iteration did not converge (ln det F = " + format_number(ln_j2) + ")");
  }
};

}  // namespace

std::unique_ptr<SolidMaterial> make_solid_material(const std::string& type, double E, double nu, double rho,
                                                   PlaneHypothesis h) {
  if (type != "svk" && type != "neo_hookean")
    throw std::invalid_argument("unknown material '" + type + "' (valid: svk, neo_hookean)");
  if (!(std::isfinite(E) && E > 0.0))
    throw std::invalid_argument("material '" + type + "': Young's modulus must be positive (got " + format_number(E) +
                                ")");
  if (!(std::isfinite(nu) && nu > -1.0 && nu < 0.5))
    throw std::invalid_argument("material '" + type + "': Poisson's ratio must lie in (-1, 0.5) (got " +
                                format_number(nu) + ")");
  if (!(std::isfinite(rho) && rho >= 0.0))
    throw std::invalid_argument("material '" + type + "': density must be non-negative (got " + format_number(rho) +
                                ")");
  if (type == "svk") return std::make_unique<SvkMaterial>(E, nu, rho, h);
  return std::make_unique<NeoHookeanMaterial>(E, nu, rho, h);
}

}  // namespace lagfsi
