// Scalar damage laws of the EFG module: Mazars (1984) and exponential damage with Mazars' equivalent strain
// (thesis §5.5-5.6, digest shared/spec/003_efg.md §2.10). History: h[0] = kappa (largest equivalent strain so
// far, at least kappa0), h[1] = damage D. See src/efg/include/lagfsi/efg/material.hpp.
#include <lagfsi/efg/material.hpp>

#include <algorithm>
#include <cmath>

namespace lagfsi::efg {

namespace {

class DamageLaw : public Material {
 public:
  DamageLaw(double E, double nu, bool ps, double kappa0) : Material(E, nu, ps), k0_(kappa0) {}
  double strain_scale() const override { return k0_; }
  std::vector<std::string> state_variables() const override { return {"kappa", "damage"}; }
  double damage(const History& h) const override { return h.h[1]; }
  void stress(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& Es) const override {
    const double et = mazars_equivalent_strain(eps, eps_zz(eps));
    const double kappa = std::max({k0_, h0.h[0], et});
    double D = kappa > k0_ ? damage_of(kappa, eps) : 0.0;
    D = std::clamp(D, 0.0, 1.0 - 1e-9);
    // Damage never decreases (a law whose weights depend on the strain state could lower it on unloading).
    D = std::max(D, h0.h[1]);
    h1.h = {kappa, D, 0.0};
    Es = (1.0 - D) * D0_;
    sig = Es * eps;
  }

 protected:
  virtual double damage_of(double kappa, const Vec3& eps) const = 0;
  double k0_;
};

class Mazars final : public DamageLaw {
 public:
  Mazars(double E, double nu, bool ps, double At, double Bt, double Ac, double Bc, double k0)
      : DamageLaw(E, nu, ps, k0), At_(At), Bt_(Bt), Ac_(Ac), Bc_(Bc) {}
  std::string type() const override { return "mazars"; }

 private:
  double damage_of(double kappa, const Vec3& eps) const override {
    const double Dt = 1 - k0_ * (1 - At_) / kappa - At_ * std::exp(-Bt_ * (kappa - k0_));
    const double Dc = 1 - k0_ * (1 - Ac_) / kappa - Ac_ * std::exp(-Bc_ * (kappa - k0_));
    // Weights from the effective stress split: eps_T = C0 <s~>+, eps_C = C0 <s~>- (principal, s3 = 0 in plane
    // stress), a_t = sum <eps_Ti> <eps_i>+ / eps~^2, a_c likewise (beta = 1).
    const Vec3 s = D0_ * eps;
    double s1, s2, th;
    principal_strains(Vec3(s[0], s[1], 2 * s[2]), s1, s2, th);  // principal values of a stress vector
    double s3 = plane_strain_ ? nu_ * (s[0] + s[1]) : 0.0;
    double e1, e2, te;
    principal_strains(eps, e1, e2, te);
    const double e3 = eps_zz(eps);
    const double sp[3] = {std::max(s1, 0.0), std::max(s2, 0.0), std::max(s3, 0.0)};
    const double sn[3] = {std::min(s1, 0.0), std::min(s2, 0.0), std::min(s3, 0.0)};
    const double ep[3] = {std::max(e1, 0.0), std::max(e2, 0.0), std::max(e3, 0.0)};
    const double trp = sp[0] + sp[1] + sp[2], trn = sn[0] + sn[1] + sn[2];
    double num_t = 0, num_c = 0, et2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double eT = ((1 + nu_) * sp[i] - nu_ * trp) / E_, eC = ((1 + nu_) * sn[i] - nu_ * trn) / E_;
      num_t += std::max(eT, 0.0) * ep[i];
      num_c += std::max(eC, 0.0) * ep[i];
      et2 += ep[i] * ep[i];
    }
    double at = 1, ac = 0;
    if (et2 > 0) {
      at = std::clamp(num_t / et2, 0.0, 1.0);
      ac = std::clamp(num_c / et2, 0.0, 1.0);
      if (at + ac > 1) {
        const double f = at + ac;
        at /= f;
        ac /= f;
      }
      if (at + ac < 1e-12) at = 1;
    }
    return at * Dt + ac * Dc;
  }
  double At_, Bt_, Ac_, Bc_;
};

class ExponentialDamage final : public DamageLaw {
 public:
  ExponentialDamage(double E, double nu, bool ps, double alpha, double beta, double k0)
      : DamageLaw(E, nu, ps, k0), a_(alpha), b_(beta) {}
  std::string type() const override { return "exponential_damage"; }

 private:
  double damage_of(double kappa, const Vec3&) const override {
    return 1 - k0_ / kappa * (1 - a_ + a_ * std::exp(-b_ * (kappa - k0_)));
  }
  double a_, b_;
};

}  // namespace

std::unique_ptr<Material> make_mazars(Params p, double E, double nu, bool ps) {
  const double At = p.non_negative("At"), Bt = p.non_negative("Bt"), Ac = p.non_negative("Ac"),
               Bc = p.non_negative("Bc"), k0 = p.positive("kappa0");
  if (At > 1) p.fail("At", "must lie in [0, 1]");
  if (Ac > 1) p.fail("Ac", "must lie in [0, 1]");
  return std::make_unique<Mazars>(E, nu, ps, At, Bt, Ac, Bc, k0);
}

std::unique_ptr<Material> make_exponential_damage(Params p, double E, double nu, bool ps) {
  const double a = p.non_negative("alpha"), b = p.non_negative("beta"), k0 = p.positive("kappa0");
  if (a > 1) p.fail("alpha", "must lie in [0, 1]");
  return std::make_unique<ExponentialDamage>(E, nu, ps, a, b, k0);
}

}  // namespace lagfsi::efg
