// Rotating total-strain smeared-crack law with Carreira & Chu (1985) compression and either fracture-energy
// regularised exponential tension softening s = f_t exp[-(e - e0)/e_f], e_f = G_f/(h f_t) - e0/2 so that the area
// under the curve is G_f/h (crack band h, fracture energy G_f; the digest's default for the
// Boone et al. 1986 law the thesis takes from Penna 2011) or Carreira & Chu (1986) tension.
// History: h[0] = largest tensile equivalent uniaxial strain, h[1] = largest compressive one (magnitude),
// h[2] = tensile damage 1 - E_s/E0. See src/efg/include/lagfsi/efg/material.hpp.
#include <lagfsi/efg/material.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::efg {

namespace {

class SmearedCrack final : public Material {
 public:
  SmearedCrack(double E, double nu, bool ps, double ft, double fc, double ec, bool cc_tension, double et, double Gf,
               double band, double residual)
      : Material(E, nu, ps), ft_(ft), fc_(fc), ec_(ec), cct_(cc_tension), et_(et), Gf_(Gf), h_(band), res_(residual) {
    bc_ = 1.0 / (1.0 - fc_ / (ec_ * E_));
    bt_ = cct_ ? 1.0 / (1.0 - ft_ / (et_ * E_)) : 0.0;
    e0_ = ft_ / E_;
    // Crack band (Bazant & Oh 1983): the whole area under the curve is G_f / h.
    ef_ = cct_ ? 1.0 : Gf_ / (h_ * ft_) - 0.5 * e0_;
  }
  std::string type() const override { return "smeared_crack"; }
  double strain_scale() const override { return e0_; }
  std::vector<std::string> state_variables() const override {
    return {"tension_strain_max", "compression_strain_max", "tension_damage"};
  }
  double damage(const History& h) const override { return h.h[2]; }

  /// Tensile envelope at equivalent strain k > 0.
  double tension(double k) const {
    if (cct_) {
      const double r = k / et_;
      return std::max(res_ * ft_, ft_ * bt_ * r / (bt_ - 1 + std::pow(r, bt_)));
    }
    if (k <= e0_) return E_ * k;
    return std::max(res_ * ft_, ft_ * std::exp(-(k - e0_) / ef_));
  }
  /// Compressive envelope (magnitude) at equivalent strain magnitude k > 0.
  double compression(double k) const {
    const double r = k / ec_;
    return std::max(res_ * fc_, fc_ * bc_ * r / (bc_ - 1 + std::pow(r, bc_)));
  }

  void stress(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& Es) const override {
    double e1, e2, th;
    principal_strains(eps, e1, e2, th);
    const double q = 1.0 / (1 - nu_ * nu_);
    const double eb[2] = {q * (e1 + nu_ * e2), q * (e2 + nu_ * e1)};
    double kt = h0.h[0], kc = h0.h[1];
    double S[2];
    double kt_new = kt, kc_new = kc;
    for (int i = 0; i < 2; ++i) {
      if (eb[i] > 0) {
        const double k = std::max(kt, eb[i]);
        kt_new = std::max(kt_new, k);
        S[i] = std::min(1.0, tension(k) / (E_ * k));
      } else if (eb[i] < 0) {
        const double k = std::max(kc, -eb[i]);
        kc_new = std::max(kc_new, k);
        S[i] = std::min(1.0, compression(k) / (E_ * k));
      } else {
        S[i] = 1.0;
      }
    }
    h1.h = {kt_new, kc_new, kt_new > 0 ? 1.0 - std::min(1.0, tension(kt_new) / (E_ * kt_new)) : 0.0};
    // Principal-frame secant operator: s_i = S_i E eb_i, shear from coaxiality.
    const double c0 = E_ * q;
    Mat3 Dp = Mat3::Zero();
    Dp(0, 0) = S[0] * c0;
    Dp(0, 1) = S[0] * c0 * nu_;
    Dp(1, 0) = S[1] * c0 * nu_;
    Dp(1, 1) = S[1] * c0;
    const double s1 = Dp(0, 0) * e1 + Dp(0, 1) * e2, s2 = Dp(1, 0) * e1 + Dp(1, 1) * e2;
    const double G0 = E_ / (2 * (1 + nu_));
    Dp(2, 2) =
        std::abs(e1 - e2) > 1e-14 ? std::clamp((s1 - s2) / (2 * (e1 - e2)), 1e-6 * G0, G0) : G0 * std::min(S[0], S[1]);
    // Engineering strain transformation eps' = T eps, sigma = T^T sigma'.
    const double c = std::cos(th), s = std::sin(th);
    Mat3 T;
    T << c * c, s * s, c * s, s * s, c * c, -c * s, -2 * c * s, 2 * c * s, c * c - s * s;
    Es = T.transpose() * Dp * T;
    sig = Es * eps;
  }

 private:
  double ft_, fc_, ec_;
  bool cct_;
  double et_, Gf_, h_, res_;
  double bc_, bt_, e0_, ef_ = 1;
};

}  // namespace

std::unique_ptr<Material> make_smeared_crack(Params p, double E, double nu, bool ps) {
  const double ft = p.positive("ft"), fc = p.positive("fc"), ec = p.positive("eps_c");
  if (fc >= ec * E) p.fail("eps_c", "Carreira-Chu needs fc < eps_c * young (beta > 1)");
  const bool cc = p.choice("tension", {"exponential", "carreira_chu"}) == "carreira_chu";
  double et = 0, Gf = 0, h = 0;
  if (cc) {
    et = p.positive("eps_t");
    if (ft >= et * E) p.fail("eps_t", "Carreira-Chu tension needs ft < eps_t * young");
  } else {
    Gf = p.positive("Gf");
    h = p.positive("band_width");
    // Snap-back of the material law itself: the softening must dissipate at least the elastic energy.
    if (ft * h / Gf >= 2 * E / ft)
      p.fail("band_width", "band too wide for Gf: h must be below 2 E Gf / ft^2 (softening snaps back)");
  }
  const double res = p.non_negative("residual");
  return std::make_unique<SmearedCrack>(E, nu, ps, ft, fc, ec, cc, et, Gf, h, res);
}

}  // namespace lagfsi::efg
