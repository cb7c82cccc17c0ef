// The EFG material interface, the linear elastic law, the finite-difference tangent and the factory.
// See src/efg/include/lagfsi/efg/material.hpp.
#include <lagfsi/efg/material.hpp>

#include <cmath>

namespace lagfsi::efg {

namespace {

/// The keys of every law, then the law's own.
std::vector<KeyDecl> law_keys(const std::string& type, std::vector<KeyDecl> own) {
  std::vector<KeyDecl> keys = {{"type", type, "`" + type + "`."},
                               {"young", nullptr, "Young's modulus E0 (Pa)."},
                               {"poisson", nullptr, "Poisson's ratio, in [0, 0.5)."},
                               {"hypothesis", "plane_stress", "plane_stress or plane_strain."}};
  for (auto& k : own) keys.push_back(std::move(k));
  return keys;
}

const KeyTable kElasticKeys("/bodies/*/material (efg body, type linear_elastic)", "Linear elasticity.",
                            law_keys("linear_elastic", {}));

const KeyTable kMazarsKeys("/bodies/*/material (efg body, type mazars)",
                           "Mazars' (1984) damage: D = a_t D_t + a_c D_c from the equivalent strain.",
                           law_keys("mazars", {{"At", nullptr, "A_t of the tensile damage D_t."},
                                               {"Bt", nullptr, "B_t of the tensile damage D_t."},
                                               {"Ac", nullptr, "A_c of the compressive damage D_c."},
                                               {"Bc", nullptr, "B_c of the compressive damage D_c."},
                                               {"kappa0", nullptr, "Damage threshold (strain)."}}));

const KeyTable kExponentialDamageKeys(
    "/bodies/*/material (efg body, type exponential_damage)",
    "D = 1 - (kappa0 / kappa) [1 - alpha + alpha exp(-beta (kappa - kappa0))], Mazars' equivalent strain.",
    law_keys("exponential_damage", {{"alpha", nullptr, "alpha (the damage reached at large strain)."},
                                    {"beta", nullptr, "beta (the rate of the damage)."},
                                    {"kappa0", nullptr, "Damage threshold (strain)."}}));

const KeyTable kSmearedCrackKeys(
    "/bodies/*/material (efg body, type smeared_crack)",
    "Rotating total-strain smeared crack: Carreira-Chu compression; exponential (fracture energy) or Carreira-Chu "
    "tension.",
    law_keys("smeared_crack",
             {{"ft", nullptr, "Tensile strength f_t (Pa)."},
              {"fc", nullptr, "Compressive strength f_c (Pa)."},
              {"eps_c", 0.002, "Strain at the compressive peak (fc < eps_c young)."},
              {"tension", "exponential", "Tension softening: exponential or carreira_chu."},
              {"Gf", 0.0, "Exponential tension: fracture energy G_f (N/m), positive."},
              {"band_width", 0.0, "Exponential tension: crack band width h (m), positive, below 2 E G_f / f_t^2."},
              {"eps_t", 0.0, "Carreira-Chu tension: strain at the tensile peak (ft < eps_t young)."},
              {"residual", 1e-4, "Residual stiffness fraction of a cracked direction, >= 0."}}));

}  // namespace

std::unique_ptr<Material> make_mazars(Params p, double E, double nu, bool ps);
std::unique_ptr<Material> make_exponential_damage(Params p, double E, double nu, bool ps);
std::unique_ptr<Material> make_smeared_crack(Params p, double E, double nu, bool ps);

Material::Material(double young, double poisson, bool plane_strain)
    : MaterialLaw(young, poisson, 0.0), plane_strain_(plane_strain) {
  if (plane_strain) {
    const double c = young / ((1 + poisson) * (1 - 2 * poisson));
    D0_ << c * (1 - poisson), c * poisson, 0, c * poisson, c * (1 - poisson), 0, 0, 0, c * (1 - 2 * poisson) / 2;
  } else {
    const double c = young / (1 - poisson * poisson);
    D0_ << c, c * poisson, 0, c * poisson, c, 0, 0, 0, c * (1 - poisson) / 2;
  }
}

double Material::eps_zz(const Vec3& eps) const { return plane_strain_ ? 0.0 : -nu_ / (1 - nu_) * (eps[0] + eps[1]); }

void Material::evaluate(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& E, Operator op) const {
  stress(eps, h0, h1, sig, E);
  if (op == Operator::secant || linear()) return;
  const double d = 1e-6 * std::max(eps.cwiseAbs().maxCoeff(), strain_scale());
  History ht;
  Vec3 s;
  Mat3 Es;
  for (int k = 0; k < 3; ++k) {
    Vec3 e = eps;
    e[k] += d;
    stress(e, h0, ht, s, Es);
    E.col(k) = (s - sig) / d;
  }
}

void principal_strains(const Vec3& eps, double& e1, double& e2, double& theta) {
  const double c = 0.5 * (eps[0] + eps[1]), r = std::hypot(0.5 * (eps[0] - eps[1]), 0.5 * eps[2]);
  e1 = c + r;
  e2 = c - r;
  theta = 0.5 * std::atan2(eps[2], eps[0] - eps[1]);
}

double mazars_equivalent_strain(const Vec3& eps, double ezz) {
  double e1, e2, th;
  principal_strains(eps, e1, e2, th);
  auto pos = [](double v) { return v > 0 ? v : 0.0; };
  return std::sqrt(pos(e1) * pos(e1) + pos(e2) * pos(e2) + pos(ezz) * pos(ezz));
}

namespace {
class LinearElastic final : public Material {
 public:
  using Material::Material;
  std::string type() const override { return "linear_elastic"; }
  bool linear() const override { return true; }
  void stress(const Vec3& eps, const History& h0, History& h1, Vec3& sig, Mat3& Es) const override {
    h1 = h0;
    Es = D0_;
    sig = D0_ * eps;
  }
};
}  // namespace

std::unique_ptr<Material> make_material(Params p) {
  if (!p.json().is_object()) p.fail("expected an object");
  if (!p.has("type")) p.fail("type", "required key is missing");
  const std::string t = p.choice("type", {"linear_elastic", "mazars", "exponential_damage", "smeared_crack"});
  auto common = [&](const KeyTable& table) { p.validate(table); };
  auto check = [&](double& E, double& nu, bool& ps) {
    E = p.positive("young");
    nu = p.number("poisson");
    if (nu < 0 || nu >= 0.5) p.fail("poisson", "must lie in [0, 0.5)");
    ps = p.choice("hypothesis", {"plane_stress", "plane_strain"}) == "plane_strain";
  };
  double E, nu;
  bool ps;
  if (t == "linear_elastic") {
    common(kElasticKeys);
    check(E, nu, ps);
    return std::make_unique<LinearElastic>(E, nu, ps);
  }
  if (t == "mazars") {
    common(kMazarsKeys);
    check(E, nu, ps);
    return make_mazars(p, E, nu, ps);
  }
  if (t == "exponential_damage") {
    common(kExponentialDamageKeys);
    check(E, nu, ps);
    return make_exponential_damage(p, E, nu, ps);
  }
  common(kSmearedCrackKeys);
  check(E, nu, ps);
  return make_smeared_crack(p, E, nu, ps);
}

}  // namespace lagfsi::efg
